"""The floor of the executor's hand-over: one thread wake-up at 1 kHz, no robomodel.

A producer thread stamps ``time.monotonic_ns()``, appends it to a deque and releases a bare lock
every 1 ms (what robomodel's Zenoh callback does with a sample); the main thread, parked in
``lock.acquire(timeout=0.05)`` as ``Executor.spin_once`` is, reads the stamp. The latency is the
cost of waking a parked thread on this machine, which rclpy's model (callbacks on the spinning
thread) pays and a callback on Zenoh's own thread does not.

Run: ``python bench/bench_handover.py [--count 3000]``.
"""

from __future__ import annotations

import argparse
import collections
import statistics
import threading
import time


def measure(count: int, period_s: float = 0.001) -> list[float]:
    """Hand-over latencies in µs, one per message, sorted."""
    stamps: collections.deque[int] = collections.deque()
    bell = threading.Lock()
    bell.acquire()  # silent, as the executor's bell

    def produce() -> None:
        due_s = time.monotonic()
        for _ in range(count):
            due_s += period_s
            while (left_s := due_s - time.monotonic()) > 0:
                time.sleep(left_s)
            stamps.append(time.monotonic_ns())
            if bell.locked():
                try:  # noqa: SIM105 (as Executor.post)
                    bell.release()
                except RuntimeError:
                    pass

    producer = threading.Thread(target=produce)
    producer.start()
    latencies_us: list[float] = []
    while producer.is_alive() or stamps:
        bell.acquire(blocking=False)
        if not stamps:
            bell.acquire(timeout=0.05)
        now_ns = time.monotonic_ns()
        while stamps:
            latencies_us.append((now_ns - stamps.popleft()) / 1000)
    producer.join()
    return sorted(latencies_us)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--count", type=int, default=3000, help="messages (default 3000)")
    args = parser.parse_args()
    lat = measure(args.count)
    p90, p99 = lat[int(len(lat) * 0.9)], lat[int(len(lat) * 0.99)]
    print(
        f"hand-over p50 {statistics.median(lat):.1f} us, p90 {p90:.1f} us, "
        f"p99 {p99:.1f} us (n={len(lat)})"
    )


if __name__ == "__main__":
    main()
