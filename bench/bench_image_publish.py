"""Publishing camera images on Zenoh: robomodel's heap setting against glibc's defaults.

A 640x480 rgb8 ``sensor_msgs/msg/Image`` (0.92 MB) published at 30 Hz by one process and
received by a robomodel subscription (its CDR payload, undecoded) in another. Two arms, run
alternately in fresh processes: ``heap`` is robomodel as it is (a process that opens a bus
between processes serves large buffers from glibc's heap, ``robomodel._heap``); ``glibc`` is the
same publisher with that setting skipped, so glibc maps and trims each image-sized buffer
afresh. Printed per arm and round: ``publish()``'s p50 and p90 [ms] in the publisher, the
latency from the stamp (``time.monotonic_ns()`` just before ``publish``) to the subscriber's
callback, and the publisher's minor page faults per image.

Run: ``PYTHONPATH=src .venv/bin/python bench/bench_image_publish.py [--seconds 5] [--rounds 3]``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from bench_bridges import _STAMP, _stamp, messages

ROOT = Path(__file__).resolve().parents[1]
TOPIC = "/camera/image"
RATE_HZ = 30.0


def publish(domain: int, seconds: float, heap: bool) -> dict[str, Any]:
    if not heap:  # glibc's defaults: the setting counts as made, so it is not
        from robomodel import _heap

        _heap._done.set()
    from robomodel.runtime import Context

    image = messages()[TOPIC]
    with Context("zenoh", domain_id=domain) as context:
        publisher = context.create_node("bench_image_pub").create_publisher(type(image), TOPIC)
        context.spin(duration_s=3.0)  # the subscriber finds the publisher
        publish_ms: list[float] = []
        faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        start = time.monotonic()
        for i in range(int(seconds * RATE_HZ)):
            time.sleep(max(0.0, start + i / RATE_HZ - time.monotonic()))
            image.header.stamp = _stamp(time.monotonic_ns())
            before = time.perf_counter_ns()
            publisher.publish(image)
            publish_ms.append((time.perf_counter_ns() - before) / 1e6)
        faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt - faults
        context.spin(duration_s=0.5)
    return {"publish_ms": publish_ms, "faults": faults}


def receive(domain: int, seconds: float) -> list[float]:
    from robomodel.runtime import Context
    from robomodel.runtime.msg import get_message_type
    from robomodel.runtime.qos import as_qos

    latencies: list[float] = []

    def on(payload: bytes, _: Any) -> None:
        sec, nanosec = _STAMP.unpack_from(payload, 4)
        latencies.append((time.monotonic_ns() - sec * 10**9 - nanosec) / 1e6)

    with Context("zenoh", domain_id=domain) as context:
        node = context.create_node("bench_image_sub")
        image = get_message_type("sensor_msgs/msg/Image")
        context.transport.create_raw_subscription(  # type: ignore[attr-defined]
            node.fully_qualified_name, TOPIC, image, as_qos(10), on
        )
        context.spin(duration_s=seconds)
    return latencies


def _p(values: list[float], q: int) -> float:
    return statistics.quantiles(values, n=100)[q - 1]


def _round(args: argparse.Namespace, heap: bool) -> tuple[dict[str, Any], list[float]]:
    me = [sys.executable, __file__, "--seconds", str(args.seconds), "--domain-id",
          str(args.domain_id)]  # fmt: skip
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    receiver = subprocess.Popen([*me, "--role", "receive"], env=env, stdout=subprocess.PIPE,
                                text=True)  # fmt: skip
    time.sleep(1.0)  # the subscriber is there before the first image
    role = "publish" if heap else "publish-glibc"
    sent = json.loads(subprocess.run([*me, "--role", role], env=env, stdout=subprocess.PIPE,
                                     text=True, check=True).stdout)  # fmt: skip
    return sent, json.loads(receiver.communicate()[0])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--domain-id", type=int, default=121)
    parser.add_argument("--role", choices=("publish", "publish-glibc", "receive"))
    args = parser.parse_args()
    if args.role == "receive":
        print(json.dumps(receive(args.domain_id, args.seconds + 5.0)))
        return
    if args.role:
        print(json.dumps(publish(args.domain_id, args.seconds, args.role == "publish")))
        return
    load = os.getloadavg()
    print(f"640x480 rgb8 image at {RATE_HZ:g} Hz on Zenoh, {args.seconds:g} s a run; load "
          f"average before {load[0]:.2f} (1 min)")  # fmt: skip
    print(f"{'round':<7}{'arm':<7}{'images':>8}{'publish p50':>13}{'p90':>8}"
          f"{'latency p50':>13}{'p90':>8}{'faults/image':>14}")  # fmt: skip
    for r in range(1, args.rounds + 1):
        for heap in (True, False):
            sent, latencies = _round(args, heap)
            publish_ms = sent["publish_ms"]
            print(f"{r:<7}{'heap' if heap else 'glibc':<7}{len(latencies):>8}"
                  f"{_p(publish_ms, 50):>13.2f}{_p(publish_ms, 90):>8.2f}"
                  f"{_p(latencies, 50):>13.2f}{_p(latencies, 90):>8.2f}"
                  f"{sent['faults'] / len(publish_ms):>14.0f}")  # fmt: skip


if __name__ == "__main__":
    main()
