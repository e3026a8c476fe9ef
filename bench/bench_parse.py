"""URDF parse time: robomodel vs pinocchio vs yourdfpy, in one process, interleaved, ratios printed.

Run: ``make bench`` or ``.venv/bin/python bench/bench_parse.py [--rounds 21]``.

Each tool reads the file from disk. robomodel: ``read_urdf`` (parse, full model, urdfdom's
checks and its own validation, source locations). pinocchio: ``buildModelFromUrdf`` (urdfdom +
model building). yourdfpy: ``URDF.load`` without meshes and without the scene graph (parsing
only). robomodel and pinocchio alternate round by round (``time_interleaved``); the ratio is
the median of the per-round ratios. The robots come from example-robot-data (test extra); the
scaling rows parse synthetic serial chains of 10, 100 and 1,000 links (inertial, box visual,
cylinder collision, revolute joint each) written to a temporary directory.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import example_robot_data, synthetic_chain_urdf, time_interleaved

ROBOTS = {
    "panda": "panda_description/urdf/panda.urdf",
    "ur5": "ur_description/urdf/ur5_robot.urdf",
    "talos_full_v2": "talos_data/robots/talos_full_v2.urdf",
    "pr2": "pr2_description/urdf/pr2.urdf",
    "tiago_dual": "tiago_description/robots/tiago_dual.urdf",
}


def _row(name: str, path: str, rounds: int, with_yourdfpy: bool) -> None:
    import pinocchio

    from robomodel.description import read_urdf

    ours, pin, ratio = time_interleaved(
        lambda: read_urdf(path), lambda: pinocchio.buildModelFromUrdf(path), rounds=rounds
    )
    ydp_text = "-"
    if with_yourdfpy:
        import yourdfpy

        _, ydp, _ = time_interleaved(
            lambda: read_urdf(path),
            lambda: yourdfpy.URDF.load(
                path, build_scene_graph=False, load_meshes=False, load_collision_meshes=False
            ),
            rounds=max(3, rounds // 3),
        )
        ydp_text = f"{ydp * 1e3:.3f} ms"
    size_kb = Path(path).stat().st_size / 1024
    print(
        f"| {name} | {size_kb:.0f} kB | {ours * 1e3:.3f} ms | {pin * 1e3:.3f} ms | "
        f"{ratio:.2f}x | {ydp_text} |"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=21)
    args = parser.parse_args()
    print(
        "| robot | size | robomodel `read_urdf` | pinocchio `buildModelFromUrdf` | ratio | yourdfpy |"
    )
    print("|---|---|---|---|---|---|")
    for name, relative in ROBOTS.items():
        _row(name, str(example_robot_data(relative)), args.rounds, with_yourdfpy=True)
    with tempfile.TemporaryDirectory() as tmp:
        for n in (10, 100, 1000):
            path = Path(tmp) / f"chain{n}.urdf"
            path.write_text(synthetic_chain_urdf(n), encoding="utf-8")
            _row(f"synthetic chain, {n} links", str(path), args.rounds, with_yourdfpy=False)


if __name__ == "__main__":
    main()
