"""Display performance: a 100,000-point PointCloud2 at 10 Hz and a 640x480 Image at 30 Hz,
from another process over Zenoh, reaching a headless browser; the viewer's CPU per message.

Run: ``.venv/bin/python bench/bench_displays.py [SECONDS] [FEED ...]`` (needs Debian's
chromium; about 3 x SECONDS + 20 s, default SECONDS 6; FEED: cloud, image, noise, bgr8, mono8
(the image feeds of ``_display_feed.py``), default cloud, image and noise).
``BENCH_VIEWPORT=WxH`` sets the page's size (default 1280x720): headless Chromium draws the 3D
view in software, and viser's client takes in websocket messages once per 3D frame, so a
smaller view shows what the page takes in when drawing the 3D view is not what limits it.

For each feed the viewer runs in this process (Frame Rate 30, RViz's default) with one display
(PointCloud2 on /bench/cloud, Image on /bench/image), headless Chromium has the page open, and ``_display_feed.py`` publishes
for SECONDS. Counted: messages sent, messages the display received, what reached Chromium
(websocket frames carrying a new point cloud or new points for a cloud's node, or a new panel
image; for the cloud also how many
clouds the display drew, each one scene update), and the drain: how long
after the last send the last of those frames arrived (a backlog shows as a drain of seconds).
For images, also what the page drew: each image carries its number in its top rows
(``_display_feed.mark_sequence``), and the page reads it back from every 640x480 ``<img>`` that
loads; counted are the different images loaded ("page"), those loaded a second while the
camera sent ("page_per_s"), the time from publishing an image to its load in the page
(latency p50 and p95), and the drain measured on those loads.
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

import numpy as np

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


# In the page: each 640x480 <img> that loads (the Image display's panel; viser's client sets
# a new blob URL per image), its load time [ms since the epoch] and the number it carries.
_PAGE_LOADS_JS = """
window.__benchLoads = [];
window.__benchFrames = [];
const tick = (t) => { window.__benchFrames.push(performance.timeOrigin + t); requestAnimationFrame(tick); };
requestAnimationFrame(tick);
document.addEventListener("load", (event) => {
  const img = event.target;
  if (!(img instanceof HTMLImageElement) || img.naturalWidth !== 640 || img.naturalHeight !== 480) return;
  const t = performance.timeOrigin + performance.now();
  const canvas = window.__benchCanvas || (window.__benchCanvas = document.createElement("canvas"));
  canvas.width = 640; canvas.height = %(rows)d;
  const ctx = canvas.getContext("2d", {willReadFrequently: true});
  ctx.drawImage(img, 0, 0);
  const d = ctx.getImageData(0, 0, 640, %(rows)d).data;
  let k = 0;
  for (let b = 0; b < %(bits)d; b++) {
    const x = b * %(width)d + %(width)d / 2, y = %(rows)d / 2;
    if (d[(y * 640 + x) * 4] > 127) k |= 1 << b;
  }
  window.__benchLoads.push([t, k]);
}, true);
"""


def _page_loads(page: Any) -> list[tuple[float, int]]:
    """The image loads the page saw since the last call: (wall time [s], image number)."""
    loads = page.evaluate("window.__benchLoads.splice(0)")
    return [(t / 1000.0, int(k)) for t, k in loads]


def _percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))] if ordered else float("nan")


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
    _page_loads(page)
    page.evaluate("window.__benchFrames.splice(0)")
    lines: list[str] = []
    reads = 1 if kind == "cloud" else 2  # "sent N", and for images "stamps ..."
    reader = threading.Thread(target=lambda: lines.extend(feed.stdout.readline() for _ in range(reads)))  # type: ignore[union-attr]  # fmt: skip
    cpu0, wall0, epoch0 = _cpu_s(), time.perf_counter(), time.time()
    feed.stdin.write("go\n")
    feed.stdin.flush()
    reader.start()
    while reader.is_alive():  # playwright hands over websocket frames only while it waits
        page.wait_for_timeout(20)
    end, epoch_end = time.perf_counter(), time.time()
    cpu1 = _cpu_s()
    sent_line = lines[0]
    page.wait_for_timeout(3000)  # frames still coming after the last send are the backlog
    feed.wait(10)
    received = display.messages_received
    # clouds put in the scene (PointCloud2Display), images encoded for the panel (ImageDisplay;
    # before it encoded on a thread of its own: images converted)
    drawn = getattr(display, "_seq", getattr(display, "sent", getattr(display, "shown", 0)))
    least = 50_000 if kind == "cloud" else 2_000  # a frame with the points, or the image

    def new_state(meta: bytes) -> bool:
        if kind != "cloud":
            return b"GuiUpdateMessage" in meta
        # a new cloud node, or new points for the node a cloud took over
        return b"PointCloudMessage" in meta or (b"SceneNodeUpdateMessage" in meta and b"points" in meta)  # fmt: skip

    shown = [t for t, size, meta in frames if new_state(meta) and size > least]
    sender = getattr(display, "sender", None)  # gone once the display is removed
    _on_loop(viewer, lambda: viewer.displays_panel.remove(viewer.displays_panel.rows[-1]))
    result = {
        "sent": float(sent_line.split()[1]),
        "received": float(received),
        "drawn": float(drawn),
        "reached_browser": float(len(shown)),
        "browser_per_s": len([t for t in shown if wall0 <= t <= end]) / (end - wall0),
        "drain_s": (max(shown) - end) if shown else float("nan"),
        "cpu_ms_per_msg": 1000 * (cpu1 - cpu0) / max(received, 1),
        "cpu_cores": (cpu1 - cpu0) / (end - wall0),
    }
    if kind != "cloud":
        stamps = [float(t) for t in lines[1].split()[1:]]
        loads = [(t, k) for t, k in _page_loads(page) if k < len(stamps)]
        ticks = [t / 1000.0 for t in page.evaluate("window.__benchFrames.splice(0)")]
        ticking = [t for t in ticks if epoch0 <= t <= epoch_end]
        first = {}
        for t, k in loads:  # an image loaded twice (the page re-rendered) counts once
            first.setdefault(k, t)
        latencies = [t - stamps[k] for k, t in first.items()]
        while_sending = [t for t in first.values() if epoch0 <= t <= epoch_end]
        result |= {
            # images replaced by a newer one before conversion (the Frame Rate's budget spent)
            # and before encoding (the encoder busy); "-1": not counted by the code measured
            "skipped": float(getattr(display, "skipped", -1)),
            "replaced": float(getattr(sender, "replaced", -1)),
            "page": float(len(first)),
            "page_per_s": len(while_sending) / (epoch_end - epoch0),
            "latency_p50_ms": 1000 * _percentile(latencies, 0.5),
            "latency_p95_ms": 1000 * _percentile(latencies, 0.95),
            "page_drain_s": (max(first.values()) - epoch_end) if first else float("nan"),
            # the page's animation frames a second while the camera sent (60: its main thread
            # was free at every display refresh)
            "page_frames_per_s": len(ticking) / (epoch_end - epoch0),
        }
    return result


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


def panel_encoding_costs() -> None:
    """The JPEG for the Image display's panel (quality 90, median of 21, ms): viser's
    ``GuiImageHandle.image`` setter (imageio, or OpenCV where installed) against Pillow's
    encoder as the display calls it."""
    import io

    from PIL import Image
    from viser._scene_api import _encode_image_binary

    sys.path.insert(0, str(ROOT / "bench"))
    from _display_feed import image_data

    for name, noise in (("camera-like", False), ("random pixels", True)):
        frames = [np.frombuffer(f, np.uint8).reshape(480, 640, 3) for f in image_data(noise)[:3]]

        def pillow(rgb: Any) -> bytes:
            out = io.BytesIO()
            Image.fromarray(rgb).save(out, format="JPEG", quality=90)
            return out.getvalue()

        viser_ms = _median_ms(lambda: [_encode_image_binary(f, "jpeg", 90) for f in frames], 21) / 3  # noqa: B023  # fmt: skip
        pillow_ms = _median_ms(lambda: [pillow(f) for f in frames], 21) / 3  # noqa: B023
        print(f"panel JPEG of a 640x480 {name} image ({len(pillow(frames[0])) / 1e3:.0f} kB): "
              f"viser's image setter {viser_ms:.1f} ms, Pillow {pillow_ms:.1f} ms")  # fmt: skip


def main() -> None:
    from playwright.sync_api import sync_playwright

    codec_costs()
    panel_encoding_costs()
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
        width, height = (int(v) for v in os.environ.get("BENCH_VIEWPORT", "1280x720").split("x"))
        page = browser.new_page(viewport={"width": width, "height": height})
        page.on("websocket", lambda ws: ws.on("framereceived", on_frame))
        sys.path.insert(0, str(ROOT / "bench"))
        from _display_feed import BIT_WIDTH_PX, MARK_ROWS, SEQUENCE_BITS

        page.add_init_script(_PAGE_LOADS_JS % {"rows": MARK_ROWS, "bits": SEQUENCE_BITS, "width": BIT_WIDTH_PX})  # fmt: skip
        page.goto(viewer.url)
        page.get_by_text("Fixed Frame", exact=True).wait_for(timeout=60000)
        cpu0, t0 = _cpu_s(), time.perf_counter()
        page.wait_for_timeout(seconds * 1000)
        idle = (_cpu_s() - cpu0) / (time.perf_counter() - t0)
        print(f"idle viewer: {idle:.3f} cores")
        for kind, rate in ((k, r) for k, r in (("cloud", 10.0), ("image", 30.0), ("noise", 30.0), ("bgr8", 30.0), ("mono8", 30.0)) if k in feeds):  # fmt: skip
            result = run(kind, rate, seconds, page, viewer, frames)
            print(f"{kind} at {rate:g} Hz: " + ", ".join(f"{k} {v:.3g}" for k, v in result.items()))  # fmt: skip
        browser.close()
        viewer.close()


if __name__ == "__main__":
    main()
