"""Simulated camera benchmark: a 320x240 camera at 30 Hz against MuJoCo's bare render.

Run: ``PYTHONPATH=src .venv/bin/python bench/bench_camera.py [--seconds 2] [--rounds 5]``.

The scene is examples/simplebot_description's simplebot_camera in worlds/wall.world, its depth
camera turned into a plain ``camera`` at 30 Hz (ROS 2 plugin form), on the in-process bus with a
subscriber to its image, physics at 1 kHz. Per round, interleaved:

1. ``--seconds`` of sim time with the camera, then the same without the camera (the sensor
   removed, everything else equal): the difference over the frames published is what one
   simulated frame costs (render, read-back, Image and CameraInfo built and delivered).
2. The bare render call on the same compiled model: ``mujoco.Renderer(model, 240, 320)``,
   ``update_scene(data, camera)`` and ``render()``, as many frames, in the same process.

Target: the simulated frame within 1.5x of the bare one. Medians over the rounds (a shared
machine). MUJOCO_GL defaults to egl here so that both use the same backend.
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")  # before mujoco is imported: the bare Renderer's

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples/simplebot_description"


def _robot(camera: bool):  # type: ignore[no-untyped-def]
    from robomodel.description.urdf.reader import read_urdf
    from robomodel.xacro import expand

    text = expand(EXAMPLE / "urdf/simplebot_camera.urdf.xacro").text
    text = text.replace('type="depth"', 'type="camera"').replace(
        "<update_rate>10</update_rate>", "<update_rate>30</update_rate>"
    )
    if not camera:
        text = re.sub(r"<sensor .*?</sensor>", "", text, flags=re.S)
    return read_urdf(text.encode(), path=str(EXAMPLE / "urdf/simplebot_camera.urdf")).robot


def _scene(camera: bool):  # type: ignore[no-untyped-def]
    from robomodel.runtime import Context, ManualClock
    from robomodel.sim import Placement, Simulation, read_world
    from robomodel.sim.bus import SimBridge

    sim = Simulation(read_world(EXAMPLE / "worlds/wall.world"))
    sim.add_robot(_robot(camera), placement=Placement(xyz_m=(0.0, 0.0, 0.076)))
    context = Context(clock=ManualClock())
    bridge = SimBridge(sim, context, ros_version=2)
    frames: list[object] = []
    if camera:
        from robomodel.runtime.msg.schema import get_message_type

        image = get_message_type("sensor_msgs/msg/Image")
        context.create_node("sub").create_subscription(
            image, "/camera/rgb/image_raw", frames.append
        )
    return sim, context, bridge, frames


def _run(camera: bool, seconds: float) -> tuple[float, int, object]:
    sim, context, bridge, frames = _scene(camera)
    sim.step(1)  # the GL context and the first frame: set-up, not the steady cost
    context.advance(0.0)
    frames.clear()
    start = time.perf_counter()
    sim.step(round(seconds / sim.model.opt.timestep))
    context.advance(0.0)
    return time.perf_counter() - start, len(frames), (sim, bridge)


def _gl_renderer() -> str:
    """The current GL context's renderer (llvmpipe: Mesa's software rasteriser)."""
    from OpenGL import GL

    return bytes(GL.glGetString(GL.GL_RENDERER)).decode()


def _bare(scene: object, frames: int) -> tuple[float, str]:
    import mujoco

    sim, bridge = scene  # type: ignore[misc]
    (camera,) = [s for s in bridge.sensors if hasattr(s, "camera_id")]
    renderer = mujoco.Renderer(sim.model, 240, 320)
    renderer.update_scene(sim.data, camera=camera.camera_id)
    renderer.render()
    start = time.perf_counter()
    for _ in range(frames):
        renderer.update_scene(sim.data, camera=camera.camera_id)
        renderer.render()
    elapsed = time.perf_counter() - start
    name = _gl_renderer()
    renderer.close()
    return elapsed / frames, name


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=2.0, help="sim time per run [s]")
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    per_frame, bare, counts = [], [], []
    for _ in range(args.rounds):
        with_camera, frames, scene = _run(True, args.seconds)
        without, _, _ = _run(False, args.seconds)
        per_frame.append((with_camera - without) / frames)
        counts.append(frames)
        seconds, renderer = _bare(scene, frames)
        bare.append(seconds)
    ours, base = statistics.median(per_frame), statistics.median(bare)
    print(f"MUJOCO_GL={os.environ['MUJOCO_GL']} ({renderer}), {args.rounds} rounds of "
          f"{args.seconds} s sim")  # fmt: skip
    print(f"frames per round (30 Hz):        {statistics.median(counts):.0f}")
    print(f"simulated camera, per frame:     {ours * 1e3:.1f} ms")
    print(f"bare MuJoCo render, per frame:   {base * 1e3:.1f} ms")
    print(f"ratio (target <= 1.5):           {ours / base:.2f}")


if __name__ == "__main__":
    main()
