"""Latency against the floor: robomodel publish -> subscription callback between two
processes, beside raw zenoh-python put -> callback with the same payload, in the same run.

Run: ``.venv/bin/python bench/bench_latency.py [--seconds 5] [--rate 1000] [--rounds 2]``.

The payload is talos' /joint_states (a ``sensor_msgs/msg/JointState`` of 32 joints, 1.2 kB of
CDR). robomodel: a node's publisher in process A, a node's subscription in process B, over the
Zenoh bus (serialisation, rmw_zenoh's attachment, the executor's hand-over to the main thread,
deserialisation). Raw: ``session.declare_publisher(key, reliability=RELIABLE).put(bytes)`` in
A (the options robomodel's publisher declares for ROS's default QoS; zenoh-python's default is
best effort) and a ``declare_subscriber`` callback in B, on sessions opened with robomodel's own Zenoh
configuration (the same router and peer links), the CDR bytes made once and only their stamp
patched per message; robomodel's side likewise publishes one JointState whose ``header.stamp``
alone is set per message (serialisation is measured, building the message is the caller's).
Both stamp the message with ``time.monotonic_ns()`` (one clock for every process of a Linux
machine) and the callback subtracts it. Rounds alternate raw and robomodel, so the shared
machine's load falls on both alike. Target: robomodel's median within 1.5x raw's.

``--profile FILE`` writes a cProfile of robomodel's subscriber process (B) to FILE;
``--decompose`` adds a third variant per round, raw put -> callback -> a queue -> the main thread
(robomodel's executor hand-over without the codecs), to tell the two costs apart;
``--best-effort`` adds raw put with zenoh-python's default options (best effort);
``--stages`` times each message's steps inside robomodel's subscriber: publish -> Zenoh's
callback, inside it, the hand-over to the executor's thread, and the executor's drain -> the
subscription callback (decoding included), as medians per round.
``--split`` adds two mixed variants per round, to tell the two ends' costs apart: robomodel's
publisher -> raw's callback, and raw's put (with rmw_zenoh's attachment, which a robomodel
subscription requires) -> robomodel's subscription.
"""

from __future__ import annotations

import argparse
import itertools
import json
import statistics
import struct
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import example_robot_data, paced_sends

ROBOT = "talos_data/robots/talos_full_v2.urdf"
TOPIC = "/bench_latency"
_STAMP_OFFSET = 4  # CDR: 4-byte encapsulation header, then header.stamp.sec, .nanosec


def _message(names: list[str], stamp_ns: int) -> Any:
    from robomodel.runtime.msg import Header, JointState, Time

    stamp = Time(stamp_ns // 1_000_000_000, stamp_ns % 1_000_000_000)
    return JointState(Header(stamp, "base_link"), names, [0.1] * len(names), [0.0] * len(names))


def _raw_key(domain: int) -> str:
    from robomodel.runtime.msg import JointState
    from robomodel.runtime.msg.typehash import dds_type_name, type_hash
    from robomodel.runtime.transport.rmw_zenoh import topic_key

    return topic_key(domain, TOPIC, dds_type_name(JointState.__typename__), type_hash(JointState))


def _stamp_ns(payload: bytes) -> int:
    sec, nanosec = struct.unpack_from("<iI", payload, _STAMP_OFFSET)
    return sec * 1_000_000_000 + nanosec


def sink_raw(domain: int, seconds: float, *, hop: bool = False) -> list[float]:
    """Raw zenoh-python's callback; with ``hop``, each payload is handed to the main thread
    through a queue first (what robomodel's executor does, without decoding)."""
    import queue

    from robomodel.runtime.transport._zenoh_session import open_session

    latencies: list[float] = []
    handed: queue.SimpleQueue[bytes] = queue.SimpleQueue()
    opened = open_session()

    def on_sample(sample: Any) -> None:
        if hop:
            handed.put(sample.payload.to_bytes())
            return
        now = time.monotonic_ns()
        latencies.append((now - _stamp_ns(sample.payload.to_bytes())) * 1e-9)

    sub = opened.session.declare_subscriber(_raw_key(domain), on_sample)
    print("ready", flush=True)
    end = time.monotonic() + seconds
    while hop and time.monotonic() < end:
        try:
            payload = handed.get(timeout=0.1)
        except queue.Empty:
            continue
        latencies.append((time.monotonic_ns() - _stamp_ns(payload)) * 1e-9)
    time.sleep(max(0.0, end - time.monotonic()))
    sub.undeclare()
    opened.session.close()
    return latencies


def sink_robomodel(
    domain: int,
    seconds: float,
    *,
    stages: list[list[float]] | None = None,
    at: dict[str, int] | None = None,
) -> list[float]:
    from robomodel.runtime import Context
    from robomodel.runtime.msg import JointState

    latencies: list[float] = []
    with Context("zenoh", domain_id=domain) as ctx:

        def on_states(msg: JointState) -> None:
            now = time.monotonic_ns()
            stamp = msg.header.stamp
            sent = stamp.sec * 1_000_000_000 + stamp.nanosec
            latencies.append((now - sent) * 1e-9)
            if stages is not None and at is not None:
                marks = (sent, at["in"], at["out"], at["drain"], now)
                steps = [(b - a) * 1e-9 for a, b in itertools.pairwise(marks)]
                stages.append([*steps, (now - sent) * 1e-9])

        ctx.create_node("sink").create_subscription(JointState, TOPIC, on_states, 1000)
        print("ready", flush=True)
        ctx.spin(duration_s=seconds)
    return latencies


def sink_robomodel_stages(domain: int, seconds: float) -> list[list[float]]:
    """As sink_robomodel, with each message's time at the subscription's Zenoh callback (entry
    and exit) and at the executor's drain: [to the callback, in it, hand-over, drain ->
    callback, total] in seconds, per message."""
    from robomodel.runtime.transport._zenoh_endpoints import ZenohSubscription

    at: dict[str, int] = {}
    on_sample, drain = ZenohSubscription._on_sample, ZenohSubscription._drain

    def timed_on_sample(self: Any, sample: Any) -> None:
        at["in"] = time.monotonic_ns()
        on_sample(self, sample)
        at["out"] = time.monotonic_ns()

    def timed_drain(self: Any) -> None:
        at["drain"] = time.monotonic_ns()
        drain(self)

    ZenohSubscription._on_sample = timed_on_sample  # type: ignore[method-assign]
    ZenohSubscription._drain = timed_drain  # type: ignore[method-assign]
    stages: list[list[float]] = []
    totals = sink_robomodel(domain, seconds, stages=stages, at=at)
    assert len(totals) == len(stages)
    return stages


def _start_sink(kind: str, domain: int, seconds: float, profile: str | None) -> Any:
    cmd = [sys.executable, __file__, "--role", kind, "--domain", str(domain)]
    cmd += ["--seconds", str(seconds)] + (["--profile", profile] if profile else [])
    sink = subprocess.Popen(cmd, stdout=subprocess.PIPE, text=True)
    assert sink.stdout is not None and sink.stdout.readline().strip() == "ready"
    return sink


def run_raw(
    names: list[str],
    domain: int,
    seconds: float,
    rate: float,
    sink_role: str = "sink-raw",
    *,
    reliable: bool = True,
    attach: bool = False,
) -> dict[str, Any]:
    import zenoh

    from robomodel.runtime.msg.cdr import serialize
    from robomodel.runtime.transport._zenoh_session import open_session
    from robomodel.runtime.transport.rmw_zenoh import encode_attachment

    sink = _start_sink(sink_role, domain, seconds + 4.0, None)
    opened = open_session()
    # robomodel's publisher's Zenoh options for its QoS (RELIABLE, KEEP_LAST: DROP), not
    # zenoh-python's defaults (BEST_EFFORT): the same delivery on both sides
    pub = opened.session.declare_publisher(
        _raw_key(domain),
        reliability=zenoh.Reliability.RELIABLE if reliable else zenoh.Reliability.DEFAULT,
        congestion_control=zenoh.CongestionControl.DROP,
    )
    template = bytearray(serialize(_message(names, 0)))
    gid = bytes(range(16))
    time.sleep(1.0)  # the sink's subscription reaches this session

    def send(k: int) -> None:
        now = time.monotonic_ns()
        struct.pack_into("<iI", template, _STAMP_OFFSET, now // 1_000_000_000, now % 1_000_000_000)
        if attach:
            pub.put(bytes(template), attachment=encode_attachment(k + 1, time.time_ns(), gid))
        else:
            pub.put(bytes(template))

    sent, elapsed = paced_sends(seconds, rate, send)
    latencies = json.loads(sink.communicate(timeout=60)[0].strip().splitlines()[-1])
    pub.undeclare()
    opened.session.close()
    return {"sent": sent, "elapsed": elapsed, "latencies": latencies, "bytes": len(template)}


def run_robomodel(
    names: list[str],
    domain: int,
    seconds: float,
    rate: float,
    profile: str | None,
    stages: bool = False,
    sink_role: str | None = None,
) -> dict[str, Any]:
    from robomodel.runtime import Context
    from robomodel.runtime.msg import JointState
    from robomodel.runtime.msg.cdr import serialize

    role = sink_role or ("sink-robomodel-stages" if stages else "sink-robomodel")
    sink = _start_sink(role, domain, seconds + 4.0, profile)
    with Context("zenoh", domain_id=domain) as ctx:
        pub = ctx.create_node("driver").create_publisher(JointState, TOPIC, 1000)
        time.sleep(1.0)  # the sink's subscription reaches this session
        template = _message(names, 0)  # as raw's: made once, only the stamp set per message
        size = len(serialize(template))
        stamp = template.header.stamp

        def send(_: int) -> None:
            now = time.monotonic_ns()
            stamp.sec, stamp.nanosec = now // 1_000_000_000, now % 1_000_000_000
            pub.publish(template)

        sent, elapsed = paced_sends(seconds, rate, send)
    got = json.loads(sink.communicate(timeout=60)[0].strip().splitlines()[-1])
    run = {"sent": sent, "elapsed": elapsed, "latencies": got, "bytes": size}
    if stages:
        run.update(latencies=[steps[-1] for steps in got], stages=got)
    return run


def _percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))]


def _summary(run: dict[str, Any]) -> str:
    lat = run["latencies"]
    return (
        f"sent {run['sent']}, received {len(lat)}; latency p50 {statistics.median(lat) * 1e6:.0f} "
        f"us, p99 {_percentile(lat, 0.99) * 1e6:.0f} us, max {max(lat) * 1e6:.0f} us"
    )


def _stage_summary(stages: list[list[float]]) -> str:
    names = ("publish -> Zenoh callback", "in it", "hand-over", "drain -> callback", "total")
    medians = (statistics.median(column) * 1e6 for column in zip(*stages, strict=True))
    return "; ".join(f"{name} {value:.0f} us" for name, value in zip(names, medians, strict=True))


def _sink_main(args: argparse.Namespace) -> None:
    roles = {
        "sink-raw": sink_raw,
        "sink-raw-hop": lambda domain, seconds: sink_raw(domain, seconds, hop=True),
        "sink-robomodel": sink_robomodel,
        "sink-robomodel-stages": sink_robomodel_stages,
    }
    role = roles[args.role]
    if args.profile:
        import cProfile

        profiler = cProfile.Profile()
        latencies = profiler.runcall(role, args.domain, args.seconds)
        profiler.dump_stats(args.profile)
    else:
        latencies = role(args.domain, args.seconds)
    print(json.dumps(latencies), flush=True)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--domain", type=int, default=78)
    parser.add_argument("--profile", default=None, metavar="FILE")
    parser.add_argument(
        "--decompose",
        action="store_true",
        help="also raw put -> callback -> queue -> main thread (robomodel's hand-over, no codec)",
    )
    parser.add_argument(
        "--best-effort",
        action="store_true",
        help="also raw put with zenoh-python's default options (best effort)",
    )
    parser.add_argument(
        "--stages",
        action="store_true",
        help="time the steps inside robomodel's subscriber process (medians per round)",
    )
    parser.add_argument(
        "--split",
        action="store_true",
        help="also robomodel's publisher -> raw callback and raw put -> robomodel's subscription",
    )
    parser.add_argument(
        "--role",
        choices=("driver", "sink-raw", "sink-raw-hop", "sink-robomodel", "sink-robomodel-stages"),
        default="driver",
    )
    args = parser.parse_args()
    if args.role != "driver":
        _sink_main(args)
        return
    from robomodel.description import read_urdf
    from robomodel.kinematics import Kinematics

    names = list(Kinematics(read_urdf(example_robot_data(ROBOT)).robot).joint_names)
    raw: list[dict[str, Any]] = []
    ours: list[dict[str, Any]] = []
    for k in range(args.rounds):
        raw.append(run_raw(names, args.domain, args.seconds, args.rate))
        print(f"round {k + 1} raw zenoh put ({raw[-1]['bytes']} B): {_summary(raw[-1])}")
        if args.best_effort:
            loose = run_raw(names, args.domain, args.seconds, args.rate, reliable=False)
            print(f"round {k + 1} raw put, best effort: {_summary(loose)}")
        if args.decompose:
            hop = run_raw(names, args.domain, args.seconds, args.rate, "sink-raw-hop")
            print(f"round {k + 1} raw put, handed to the main thread: {_summary(hop)}")
        if args.split:
            mixed = run_robomodel(
                names, args.domain, args.seconds, args.rate, None, False, "sink-raw"
            )
            print(f"round {k + 1} robomodel publisher -> raw callback: {_summary(mixed)}")
            mixed = run_raw(
                names, args.domain, args.seconds, args.rate, "sink-robomodel", attach=True
            )
            print(f"round {k + 1} raw put -> robomodel subscription: {_summary(mixed)}")
        ours.append(
            run_robomodel(names, args.domain, args.seconds, args.rate, args.profile, args.stages)
        )
        print(f"round {k + 1} robomodel ({ours[-1]['bytes']} B CDR): {_summary(ours[-1])}")
        if args.stages:
            print(f"round {k + 1} robomodel's steps: {_stage_summary(ours[-1]['stages'])}")
    med = statistics.median
    for q, label in ((0.5, "p50"), (0.99, "p99")):
        theirs = med(_percentile(r["latencies"], q) for r in raw)
        mine = med(_percentile(r["latencies"], q) for r in ours)
        print(
            f"{label} median over rounds: robomodel {mine * 1e6:.0f} us, raw zenoh "
            f"{theirs * 1e6:.0f} us, ratio {mine / theirs:.2f}x (target <= 1.5x)"
        )


if __name__ == "__main__":
    main()
