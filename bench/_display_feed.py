"""A publisher process for bench_displays.py: ``_display_feed.py KIND DOMAIN RATE_HZ SECONDS``.

KIND ``cloud``: a 100,000-point PointCloud2 (x, y, z, intensity float32; 16-byte points) on
/bench/cloud (seven different clouds in turn); ``image``: a 640x480 rgb8 Image on /bench/image (seven frames in turn); ``noise``: the
same with random pixels; ``bgr8``, ``mono8``: the camera-like frames in that encoding (grey: their
mean). Messages are built once and
re-stamped; sends follow ``paced_sends`` (never accumulated). Prints ``ready`` when its
publisher exists, then ``sent N`` at the end, and for images ``stamps T0 T1 ...``: the wall
time [s] each image was published, image k carrying k in its top rows (:func:`mark_sequence`,
read back by the page in bench_displays.py).
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


SEQUENCE_BITS, BIT_WIDTH_PX, MARK_ROWS = 16, 40, 16


IMAGE_ENCODINGS = {"image": "rgb8", "noise": "rgb8", "bgr8": "bgr8", "mono8": "mono8"}  # by KIND


def in_encoding(frame: bytes, encoding: str) -> bytes:
    """An rgb8 640x480 ``frame`` as ``encoding`` (rgb8, bgr8 or mono8: the channels' mean)."""
    rgb = np.frombuffer(frame, np.uint8).reshape(480, 640, 3)
    if encoding == "bgr8":
        return np.ascontiguousarray(rgb[..., ::-1]).tobytes()
    if encoding == "mono8":
        return rgb.mean(axis=2).astype(np.uint8).tobytes()
    return frame


def mark_sequence(frame: bytes, k: int, width: int = 640, channels: int = 3) -> bytes:
    """A ``frame`` (``channels`` bytes a pixel) with ``k`` written in its top ``MARK_ROWS``
    rows: bit b (LSB first) a white or black block ``BIT_WIDTH_PX`` wide from
    x = b * BIT_WIDTH_PX, whole JPEG blocks that survive the viewer's encoding."""
    pixels = np.frombuffer(frame, np.uint8).reshape(-1, width, channels).copy()
    for b in range(SEQUENCE_BITS):
        pixels[:MARK_ROWS, b * BIT_WIDTH_PX : (b + 1) * BIT_WIDTH_PX] = 255 if k >> b & 1 else 0
    return pixels.tobytes()


def image_message(encoding: str = "rgb8") -> object:
    Image = get_message_type("sensor_msgs/msg/Image")
    channels = 1 if encoding == "mono8" else 3
    msg = Image(height=480, width=640, encoding=encoding, step=640 * channels,
                data=in_encoding(image_data()[0], encoding))  # fmt: skip
    msg.header.frame_id = "map"
    return msg


def main() -> None:
    kind, domain, rate_hz, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])  # fmt: skip
    encoding = IMAGE_ENCODINGS.get(kind, "")
    msg = cloud_message() if kind == "cloud" else image_message(encoding)
    # seven different clouds in turn, as a lidar's differ (the same one again would not be
    # sent to the page again: viser skips a node update that changes nothing)
    if kind == "cloud":
        frames = [cloud_data(k) for k in range(7)]
    else:
        frames = [in_encoding(f, encoding) for f in image_data(kind == "noise")]
    channels = 1 if encoding == "mono8" else 3
    context = Context("zenoh", domain_id=domain)
    node = context.create_node("bench_feed")
    pub = node.create_publisher(type(msg), f"/bench/{'cloud' if kind == 'cloud' else 'image'}", 10)
    print("ready", flush=True)
    sys.stdin.readline()  # the bench says when the viewer listens

    stamps: list[float] = []

    def send(k: int) -> None:
        frame = frames[k % len(frames)]
        msg.data = frame if kind == "cloud" else mark_sequence(frame, k, channels=channels)  # type: ignore[attr-defined]
        ns = time.time_ns()
        msg.header.stamp.sec, msg.header.stamp.nanosec = divmod(ns, 1_000_000_000)  # type: ignore[attr-defined]
        pub.publish(msg)
        stamps.append(ns / 1e9)

    sent, _elapsed = paced_sends(seconds, rate_hz, send)
    print(f"sent {sent}", flush=True)
    if kind != "cloud":
        print("stamps " + " ".join(f"{t:.6f}" for t in stamps), flush=True)
    time.sleep(1.0)
    context.shutdown()


if __name__ == "__main__":
    main()
