"""URDF parse time: robomodel vs pinocchio vs yourdfpy, in one process, ratio printed.

Run: ``make bench`` or ``.venv/bin/python bench/bench_parse.py``.

Each tool reads the file from disk. robomodel: ``read_urdf`` (parse, full model, urdfdom's
checks and its own validation). pinocchio: ``buildModelFromUrdf`` (urdfdom + model building).
yourdfpy: ``URDF.load`` without meshes and without the scene graph (parsing only).
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import example_robot_data, time_call

ROBOTS = {
    "panda": "panda_description/urdf/panda.urdf",
    "ur5": "ur_description/urdf/ur5_robot.urdf",
    "talos_full_v2": "talos_data/robots/talos_full_v2.urdf",
}


def main() -> None:
    import pinocchio
    import yourdfpy

    from robomodel.description import read_urdf

    print(
        f"{'robot':<15}{'robomodel':>12}{'pinocchio':>12}{'yourdfpy':>12}{'ours/pin':>10}{'yourdfpy/ours':>15}"
    )
    for name, relative in ROBOTS.items():
        path = str(example_robot_data(relative))
        ours = time_call(lambda p=path: read_urdf(p))
        pin = time_call(lambda p=path: pinocchio.buildModelFromUrdf(p))
        ydp = time_call(
            lambda p=path: yourdfpy.URDF.load(
                p, build_scene_graph=False, load_meshes=False, load_collision_meshes=False
            )
        )
        print(
            f"{name:<15}{ours * 1e3:>10.3f}ms{pin * 1e3:>10.3f}ms{ydp * 1e3:>10.3f}ms"
            f"{ours / pin:>10.2f}{ydp / ours:>15.2f}"
        )


if __name__ == "__main__":
    main()
