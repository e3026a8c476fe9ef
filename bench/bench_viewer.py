"""`robomodel view` benchmarks on talos_full_v2 (60 links, 48 visual + 47 collision STL meshes).

Run: ``.venv/bin/python bench/bench_viewer.py`` (needs Debian's chromium for the second part).

1. Cold start: a fresh ``robomodel view`` process until ``GET /`` answers 200 (the page is
   served), median of several runs; also until the process reports every mesh loaded.
   Target: page served <= 1.5 s (excluding the browser).
2. State updates reaching a connected browser: the viewer runs in this process, headless
   Chromium loads the page, a driver thread moves every joint at 240 Hz through
   joint_state_publisher (the sliders' path: /joint_states -> robot_state_publisher -> /tf ->
   the viewer's TF buffer -> poses in the fixed frame -> viser), and the websocket frames that
   carry link poses are counted as Chromium receives them (playwright ``framereceived``).
   Target: >= 60 updates/s.
3. Scaling: the same measurement at Frame Rate 240 on synthetic chains of 10, 100
   and 1,000 links (a box per link, a revolute joint between each two) and on talos. Target:
   the rate falls no faster than linearly with the links; >= 30 updates/s at 1,000 links and
   >= 100/s on talos.

``--scaling`` runs only part 3; ``--scaling --socket`` runs it with a plain websocket reader
process (``_ws_count.py``) in place of Chromium: what the viewer can send when no browser
shares the machine.
"""

from __future__ import annotations

import dataclasses
import math
import os
import statistics
import subprocess
import sys
import threading
import time
import urllib.request
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np

from _common import example_robot_data

URDF = example_robot_data("talos_data/robots/talos_full_v2.urdf")
PACKAGE = f"example-robot-data={example_robot_data('').parent}"
RUNS = 7


def cold_start(port: int) -> tuple[float, float]:
    """(seconds to HTTP 200 on the page, seconds to 'scene ready') for one fresh process."""
    cmd = [sys.executable, "-m", "robomodel.cli.main", "view", str(URDF), "--package", PACKAGE]
    cmd += ["--no-browser", "--port", str(port)]
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    served = math.nan
    while time.perf_counter() - start < 30:
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=1) as answer:
                if answer.status == 200:
                    served = time.perf_counter() - start
                    break
        except OSError:
            time.sleep(0.005)
    ready = math.nan
    assert proc.stderr is not None
    for line in proc.stderr:
        if "scene ready" in line:
            ready = time.perf_counter() - start
            break
    proc.terminate()
    proc.wait()
    return served, ready


def chain_urdf(n_links: int) -> str:
    """A serial chain of ``n_links`` links (a box each), revolute joints about y."""
    parts = ['<?xml version="1.0"?>', f'<robot name="chain{n_links}">']
    box = '<visual><geometry><box size="0.02 0.02 0.1"/></geometry></visual>'
    parts += [f'  <link name="link{i}">{box}</link>' for i in range(n_links)]
    for i in range(1, n_links):
        parts.append(
            f'  <joint name="joint{i}" type="revolute"><parent link="link{i - 1}"/>'
            f'<child link="link{i}"/><origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>'
            '<limit lower="-0.2" upper="0.2" effort="1" velocity="1"/></joint>'
        )
    parts.append("</robot>")
    return "\n".join(parts)


def _viewer_and_marker(frame_rate_hz: float | None, urdf: Path) -> tuple[Any, list[Any], str]:
    """A started viewer of ``urdf``, its slider joints and the scene node counted as updates.

    One scene update = one new orientation of the deepest link (it moves whenever any joint
    does). Counting websocket frames instead would count a big update once per frame that
    viser splits it into, and count nothing for updates that viser merged before sending.
    """
    from robomodel.description.packages import index_from_options
    from robomodel.viewer import RobotSource, Viewer, ViewerOptions

    options = ViewerOptions(
        sources=(RobotSource(str(urdf)),),
        port=0,
        package_index=index_from_options((), (PACKAGE,)),
    )
    if frame_rate_hz is not None:
        options = dataclasses.replace(options, frame_rate_hz=frame_rate_hz)
    viewer = Viewer(options)
    viewer.start()
    viewer.meshes_ready.wait(60)
    session = viewer.sessions[0]
    assert session.jsp is not None and viewer.context is not None
    joints = list(session.jsp.free_joints.values())
    display = session.display
    assert display is not None and session.robot is not None
    depth = {joint.child: d for d, joint in session.robot.tree().walk()}
    deepest = max(display.link_names, key=lambda name: depth.get(name, 0))
    return viewer, joints, f"{display.root}/l{display.link_names.index(deepest)}"


def _drive_sliders(session: Any, joints: list[Any], stop: threading.Event) -> None:
    """Move every slider joint at 240 Hz until ``stop`` (what dragging sliders does).

    Every joint's value is one numpy expression: the driver stands in for the browser's
    slider events (each one value, handled on viser's thread), so it must not itself take a
    share of the GIL that grows with the robot (a per-joint Python loop at 240 Hz cost a third
    of a core at 1,000 joints, more than robot_state_publisher).
    """
    names = [j.name for j in joints]
    low = np.array([j.min for j in joints])
    span = np.array([j.max - j.min for j in joints])
    phase = np.arange(len(joints), dtype=float)
    t0 = time.perf_counter()
    while not stop.is_set():
        t = time.perf_counter() - t0
        values = low + span * (0.5 + 0.4 * np.sin(2 * t + phase))
        session.queue_positions(dict(zip(names, values.tolist(), strict=True)))
        time.sleep(1 / 240)


def updates_per_second_socket(urdf: Path, duration_s: float = 5.0) -> tuple[float, float]:
    """(scene updates/s received, pushes/s) with a plain websocket reader instead of Chromium.

    The reader (``_ws_count.py``) runs in a process of its own and only decodes what it
    receives: what the viewer's side can send when no browser shares the machine's two cores.
    """
    viewer, joints, marker = _viewer_and_marker(240.0, urdf)
    stop = threading.Event()
    driver = threading.Thread(
        target=_drive_sliders, args=(viewer.sessions[0], joints, stop), daemon=True
    )
    driver.start()
    sent0, started = viewer.updates_sent, time.perf_counter()
    reader = Path(__file__).resolve().parent / "_ws_count.py"
    url = viewer.url.replace("http://", "ws://")
    out = subprocess.run(
        [sys.executable, str(reader), url, marker, str(duration_s)],
        capture_output=True,
        text=True,
        check=True,
    )
    pushed = (viewer.updates_sent - sent0) / (time.perf_counter() - started)
    stop.set()
    driver.join()
    viewer.close()
    return float(out.stdout.split()[-1]), pushed


def updates_per_second(
    frame_rate_hz: float | None = None, duration_s: float = 5.0, urdf: Path = URDF
) -> tuple[float, float, float]:
    """(scene updates/s received by Chromium, pushes/s sent by the viewer, websocket frames/s
    carrying poses: an older measure, which counts a split update several times).

    ``frame_rate_hz`` None: the viewer's default Frame Rate (the cap on scene updates).
    """
    from playwright.sync_api import sync_playwright

    viewer, joints, marker = _viewer_and_marker(frame_rate_hz, urdf)
    session = viewer.sessions[0]
    marker_bytes = marker.encode()
    frames: list[float] = []
    pose_frames: list[float] = []

    import msgspec
    import zstandard

    def on_frame(payload: bytes | str) -> None:
        # viser's wire format: [u64 raw size][u64 zstd size][zstd msgpack][binary buffers]
        if not isinstance(payload, bytes) or len(payload) < 16:
            return
        size = int.from_bytes(payload[8:16], "little")
        meta = zstandard.ZstdDecompressor().decompress(payload[16 : 16 + size])
        if b"SetOrientationMessage" not in meta:
            return
        pose_frames.append(time.perf_counter())
        if marker_bytes not in meta:
            return
        for message in msgspec.msgpack.decode(meta)["messages"]:
            if message.get("type") == "SetOrientationMessage" and message.get("name") == marker:
                frames.append(time.perf_counter())

    with sync_playwright() as pw:
        browser = pw.chromium.launch(
            executable_path="/usr/bin/chromium",
            headless=True,
            args=["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run"],
        )
        page = browser.new_page(viewport={"width": 1280, "height": 720})
        page.on("websocket", lambda ws: ws.on("framereceived", on_frame))
        page.goto(viewer.url)
        page.get_by_text("Fixed Frame", exact=True).wait_for(timeout=60000)
        page.wait_for_timeout(2000)
        stop = threading.Event()

        sent0 = viewer.updates_sent
        frames.clear()
        pose_frames.clear()
        driver = threading.Thread(target=_drive_sliders, args=(session, joints, stop), daemon=True)
        started = time.perf_counter()
        driver.start()
        page.wait_for_timeout(duration_s * 1000)
        elapsed = time.perf_counter() - started
        stop.set()
        driver.join()
        sent = viewer.updates_sent - sent0
        received = len([f for f in frames if f - started <= elapsed])
        browser.close()
    viewer.close()
    pose_frame_rate = len([f for f in pose_frames if f - started <= elapsed]) / elapsed
    return received / elapsed, sent / elapsed, pose_frame_rate


def scaling(rounds: int = 3, *, socket: bool = False) -> None:
    """Updates/s received at Frame Rate 240 against robot size (part 3)."""
    import tempfile

    reader = "a websocket reader process, no browser" if socket else "headless Chromium"
    print(f"scaling at Frame Rate 240 (median of {rounds} runs of 5 s; {reader}):")
    print(
        "| robot | links | updates/s received | viewer pushes/s | links x updates/s "
        "| pose frames/s (old measure) |"
    )
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        robots: list[tuple[str, int, Path]] = []
        for n_links in (10, 100, 1000):
            path = Path(tmp) / f"chain{n_links}.urdf"
            path.write_text(chain_urdf(n_links))
            robots.append((f"chain{n_links}", n_links, path))
        if URDF.exists():
            robots.append(("talos_full_v2", 60, URDF))
        for label, n_links, path in robots:
            if socket:
                sock = [updates_per_second_socket(path) for _ in range(rounds)]
                received = statistics.median(r[0] for r in sock)
                pushed = statistics.median(r[1] for r in sock)
                print(
                    f"| {label} | {n_links} | {received:.0f} | {pushed:.0f} | "
                    f"{n_links * received:,.0f} | - |"
                )
                continue
            rates = [updates_per_second(240.0, urdf=path) for _ in range(rounds)]
            received = statistics.median(r[0] for r in rates)
            pushed = statistics.median(r[1] for r in rates)
            pose_frames = statistics.median(r[2] for r in rates)
            print(
                f"| {label} | {n_links} | {received:.0f} | {pushed:.0f} | "
                f"{n_links * received:,.0f} | {pose_frames:.0f} |"
            )


def main() -> None:
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    if "--scaling" in sys.argv[1:]:
        scaling(socket="--socket" in sys.argv[1:])
        return
    print(f"robot: {URDF.name} (60 links, 48 visual + 47 collision meshes)")
    served, ready = [], []
    for i in range(RUNS):
        s, r = cold_start(18700 + i)
        served.append(s)
        ready.append(r)
    print(
        f"cold start to page served: median {statistics.median(served):.2f} s "
        f"(min {min(served):.2f}, max {max(served):.2f}; target <= 1.5 s)"
    )
    print(f"cold start to every visual mesh in the scene: median {statistics.median(ready):.2f} s")
    from robomodel.viewer import ViewerOptions

    default_hz = ViewerOptions(sources=()).frame_rate_hz
    for frame_rate_hz in (None, 240.0):
        rates = [updates_per_second(frame_rate_hz) for _ in range(3)]
        received = statistics.median(r[0] for r in rates)
        pushed = statistics.median(r[1] for r in rates)
        print(
            f"pose updates received by Chromium at Frame Rate {frame_rate_hz or default_hz:.0f}: "
            f"median {received:.0f}/s (viewer pushed {pushed:.0f}/s; target >= 60/s)"
        )
    scaling()


if __name__ == "__main__":
    main()
