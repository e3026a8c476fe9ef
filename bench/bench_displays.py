"""Issue 31's display performance: a 100,000-point PointCloud2 at 10 Hz and a 640x480 Image at
30 Hz, from another process over Zenoh, reaching a headless browser; the viewer's CPU per
message.

Run: ``.venv/bin/python bench/bench_displays.py [SECONDS] [FEED ...]`` (needs Debian's
chromium; about 3 x SECONDS + 20 s, default SECONDS 6; FEED: cloud, image, noise, default all).

For each feed the viewer runs in this process (Frame Rate 30, RViz's default) with one display
(PointCloud2 on /bench/cloud, Image on /bench/image), headless Chromium has the page open, and ``_display_feed.py`` publishes
for SECONDS. Counted: messages sent, messages the display received, what reached Chromium
(websocket frames carrying a new point cloud or new points for a cloud's node, or a new panel
image; for the cloud also how many
clouds the display drew, each one scene update), and the drain: how long
after the last send the last of those frames arrived (a backlog shows as a drain of seconds).
CPU: this process's user + system time during the feed less its main thread's (the viewer's
threads; the main thread runs the bench and playwright's client, which decodes every frame
Chromium reports; Chromium and the publisher are other processes), per message received, and
an idle viewer's for comparison.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
DOMAIN = int(os.environ.get("ROBOMODEL_BENCH_DOMAIN", "139"))  # another run at once: another domain


def _cpu_s() -> float:
    """The viewer's CPU time [s]: this process's, less the main thread's (the bench and
    playwright's client, which decodes every websocket frame Chromium reports)."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime - time.thread_time()


def _viewer(tmp: Path) -> Any:
    from robomodel.viewer import RobotSource, Viewer, ViewerOptions

    urdf = tmp / "frame_only.urdf"
    urdf.write_text('<?xml version="1.0"?><robot name="f"><link name="map"/></robot>\n')
    # Frame Rate 30: RViz's default, at which its Image display shows new images
    options = ViewerOptions(sources=(RobotSource(str(urdf)),), port=0, bus="zenoh",
                            domain_id=DOMAIN, fixed_frame="map", tools=False,
                            frame_rate_hz=30.0)  # fmt: skip
    viewer = Viewer(options)
    viewer.start()
    return viewer


def _on_loop(viewer: Any, work: Any) -> Any:
    done, box = threading.Event(), []
    viewer._post(lambda: (box.append(work()), done.set()))
    done.wait(10)
    return box[0]


def run(kind: str, rate_hz: float, seconds: float, page: Any, viewer: Any, frames: list[tuple[float, int, bytes]]) -> dict[str, float]:  # fmt: skip
    display_class, name = ("PointCloud2", "Cloud") if kind == "cloud" else ("Image", "Image")
    topic = "/bench/cloud" if kind == "cloud" else "/bench/image"
    display = _on_loop(viewer, lambda: viewer.displays_panel.add(display_class, name=name, values={"Topic": topic}))  # fmt: skip
    feed_args = [kind, str(DOMAIN), str(rate_hz), str(seconds)]
    feed = subprocess.Popen(
        [sys.executable, str(ROOT / "bench" / "_display_feed.py"), *feed_args],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    assert feed.stdout is not None and feed.stdin is not None
    assert feed.stdout.readline().strip() == "ready"
    deadline = time.monotonic() + 20
    while not _on_loop(viewer, lambda: bool(viewer.displays.displays)) and time.monotonic() < deadline:  # fmt: skip
        time.sleep(0.1)
    page.wait_for_timeout(2000)  # the subscription and its route settle
    frames.clear()
    lines: list[str] = []
    reader = threading.Thread(target=lambda: lines.append(feed.stdout.readline()))  # type: ignore[union-attr]
    cpu0, wall0 = _cpu_s(), time.perf_counter()
    feed.stdin.write("go\n")
    feed.stdin.flush()
    reader.start()
    while reader.is_alive():  # playwright hands over websocket frames only while it waits
        page.wait_for_timeout(20)
    end = time.perf_counter()
    cpu1 = _cpu_s()
    sent_line = lines[0]
    page.wait_for_timeout(3000)  # frames still coming after the last send are the backlog
    feed.wait(10)
    received = display.messages_received
    # clouds put in the scene (PointCloud2Display), images sent to the panel (ImageDisplay)
    drawn = getattr(display, "_seq", getattr(display, "shown", 0))
    least = 50_000 if kind == "cloud" else 5_000  # a frame with the points, or the image

    def new_state(meta: bytes) -> bool:
        if kind != "cloud":
            return b"GuiUpdateMessage" in meta
        # a new cloud node, or new points for the node a cloud took over
        return b"PointCloudMessage" in meta or (b"SceneNodeUpdateMessage" in meta and b"points" in meta)  # fmt: skip

    shown = [t for t, size, meta in frames if new_state(meta) and size > least]
    _on_loop(viewer, lambda: viewer.displays_panel.remove(viewer.displays_panel.rows[-1]))
    return {
        "sent": float(sent_line.split()[1]),
        "received": float(received),
        "drawn": float(drawn),
        "reached_browser": float(len(shown)),
        "browser_per_s": len([t for t in shown if wall0 <= t <= end]) / (end - wall0),
        "drain_s": (max(shown) - end) if shown else float("nan"),
        "cpu_ms_per_msg": 1000 * (cpu1 - cpu0) / max(received, 1),
        "cpu_cores": (cpu1 - cpu0) / (end - wall0),
    }


def _median_ms(work: Any, runs: int = 7) -> float:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        work()
        times.append(time.perf_counter() - start)
    return 1000 * sorted(times)[runs // 2]


def codec_costs() -> None:
    """Where a message's time goes in the viewer: CDR decoding, the uint8[] list back to
    bytes, and the display's conversion (median of 7, ms)."""
    sys.path.insert(0, str(ROOT / "bench"))
    from _display_feed import cloud_message, image_message
    from robomodel.runtime.msg import deserialize, serialize
    from robomodel.viewer.displays.cloud import decode_cloud, message_bytes
    from robomodel.viewer.displays.image import image_rgb

    for name, msg, convert in (("cloud 100k", cloud_message(), decode_cloud),
                               ("image 640x480", image_message(), image_rgb)):  # fmt: skip
        payload = serialize(msg)
        decoded = deserialize(payload, type(msg))
        as_bytes = type(msg)(**{**msg.__dict__, "data": message_bytes(decoded.data)}) if hasattr(msg, "__dict__") else msg  # fmt: skip
        print(
            f"{name} ({len(payload) / 1e6:.2f} MB): CDR decode {_median_ms(lambda: deserialize(payload, type(msg))):.1f} ms"  # noqa: B023
            f" (uint8[] as a list of ints), list -> bytes {_median_ms(lambda: message_bytes(decoded.data)):.1f} ms,"  # noqa: B023
            f" display conversion {_median_ms(lambda: convert(decoded)):.1f} ms from the list,"  # noqa: B023
            f" {_median_ms(lambda: convert(as_bytes)):.1f} ms from bytes"  # noqa: B023
        )


def main() -> None:
    from playwright.sync_api import sync_playwright

    codec_costs()
    seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 6.0
    feeds = sys.argv[2:] or ["cloud", "image", "noise"]
    frames: list[tuple[float, int, bytes]] = []

    def on_frame(payload: bytes | str) -> None:
        if isinstance(payload, bytes) and len(payload) > 16:
            import zstandard

            size = int.from_bytes(payload[8:16], "little")
            try:
                meta = zstandard.ZstdDecompressor().decompress(
                    payload[16 : 16 + size], max_output_size=1 << 26
                )
            except Exception as exc:
                meta = repr(exc).encode()
            # only what the bench looks for: a frame may carry megabytes of image data
            tokens = (b"PointCloudMessage", b"GuiUpdateMessage", b"SceneNodeUpdateMessage", b"points")  # fmt: skip
            found = b" ".join(m for m in tokens if m in meta)
            frames.append((time.perf_counter(), len(payload), found))

    with tempfile.TemporaryDirectory() as tmp, sync_playwright() as pw:
        viewer = _viewer(Path(tmp))
        browser = pw.chromium.launch(executable_path="/usr/bin/chromium", headless=True,
                                     args=["--no-sandbox", "--disable-gpu", "--disable-quic"])  # fmt: skip
        page = browser.new_page(viewport={"width": 1280, "height": 720})
        page.on("websocket", lambda ws: ws.on("framereceived", on_frame))
        page.goto(viewer.url)
        page.get_by_text("Fixed Frame", exact=True).wait_for(timeout=60000)
        cpu0, t0 = _cpu_s(), time.perf_counter()
        page.wait_for_timeout(seconds * 1000)
        idle = (_cpu_s() - cpu0) / (time.perf_counter() - t0)
        print(f"idle viewer: {idle:.3f} cores")
        for kind, rate in ((k, r) for k, r in (("cloud", 10.0), ("image", 30.0), ("noise", 30.0)) if k in feeds):  # fmt: skip
            result = run(kind, rate, seconds, page, viewer, frames)
            print(f"{kind} at {rate:g} Hz: " + ", ".join(f"{k} {v:.3g}" for k, v in result.items()))  # fmt: skip
        browser.close()
        viewer.close()


if __name__ == "__main__":
    main()
