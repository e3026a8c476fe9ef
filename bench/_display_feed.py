"""A publisher process for bench_displays.py: ``_display_feed.py KIND DOMAIN RATE_HZ SECONDS``.

KIND ``cloud``: a 100,000-point PointCloud2 (x, y, z, intensity float32; 16-byte points) on
/bench/cloud (seven different clouds in turn); ``image``: a 640x480 rgb8 Image on /bench/image (seven frames in turn); ``noise``: the
same with random pixels. Messages are built once and
re-stamped; sends follow ``paced_sends`` (never accumulated). Prints ``ready`` when its
publisher exists, then ``sent N`` at the end.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np

from _common import paced_sends
from robomodel.runtime.context import Context
from robomodel.runtime.msg import get_message_type


def cloud_data(seed: int = 0, n: int = 100_000) -> bytes:
    """``n`` points (x, y, z, intensity float32) uniform in a 10 m cube, intensity 0-100."""
    rng = np.random.default_rng(seed)
    xyzi = np.concatenate([rng.uniform(-5, 5, (n, 3)), rng.uniform(0, 100, (n, 1))], axis=1)
    return xyzi.astype(np.float32).tobytes()


def cloud_message() -> object:
    PointCloud2 = get_message_type("sensor_msgs/msg/PointCloud2")
    PointField = get_message_type("sensor_msgs/msg/PointField")
    n = 100_000
    msg = PointCloud2(height=1, width=n, point_step=16, row_step=16 * n, is_dense=True)
    msg.fields = [
        PointField(name=name, offset=4 * i, datatype=7, count=1)
        for i, name in enumerate(("x", "y", "z", "intensity"))
    ]
    msg.data = cloud_data(0, n)
    msg.header.frame_id = "map"
    return msg


def image_data(noise: bool = False) -> list[bytes]:
    """Seven different 640x480 rgb8 frames (an unchanged image is not sent to the page again,
    and the viewer draws at 10 Hz: with three frames every third would look the same): a
    camera-like scene (gradients and a bar that moves, ~40 kB as JPEG) or, with ``noise``,
    random pixels (the worst case for JPEG: ~280 kB)."""
    if noise:
        base = np.random.default_rng(0).integers(0, 256, (480, 640, 3), dtype=np.uint8)
    else:
        y, x = np.mgrid[0:480, 0:640]
        base = np.stack([x * 255 // 639, y * 255 // 479, (x + y) * 255 // 1118], axis=2)
        base = base.astype(np.uint8)
        base[200:280, 100:140] = (255, 255, 255)
    return [np.roll(base, 40 * k, axis=1).tobytes() for k in range(7)]


def image_message() -> object:
    Image = get_message_type("sensor_msgs/msg/Image")
    msg = Image(height=480, width=640, encoding="rgb8", step=640 * 3, data=image_data()[0])
    msg.header.frame_id = "map"
    return msg


def main() -> None:
    kind, domain, rate_hz, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])  # fmt: skip
    msg = cloud_message() if kind == "cloud" else image_message()
    # seven different clouds in turn, as a lidar's differ (the same one again would not be
    # sent to the page again: viser skips a node update that changes nothing)
    frames = [cloud_data(k) for k in range(7)] if kind == "cloud" else image_data(kind == "noise")
    context = Context("zenoh", domain_id=domain)
    node = context.create_node("bench_feed")
    pub = node.create_publisher(type(msg), f"/bench/{'cloud' if kind == 'cloud' else 'image'}", 10)
    print("ready", flush=True)
    sys.stdin.readline()  # the bench says when the viewer listens

    def send(k: int) -> None:
        msg.data = frames[k % len(frames)]  # type: ignore[attr-defined]
        ns = time.time_ns()
        msg.header.stamp.sec, msg.header.stamp.nanosec = divmod(ns, 1_000_000_000)  # type: ignore[attr-defined]
        pub.publish(msg)

    sent, _elapsed = paced_sends(seconds, rate_hz, send)
    print(f"sent {sent}", flush=True)
    time.sleep(1.0)
    context.shutdown()


if __name__ == "__main__":
    main()
