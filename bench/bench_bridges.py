"""foxglove_bridge's latency against robomodel's own subscriber: 1 kHz /joint_states and a
640x480 rgb8 image at 30 Hz, published in one process, received by a robomodel subscription in
another and, through ``robomodel run foxglove_bridge foxglove_bridge``, by a Foxglove client in a
third: ``node`` is ``@foxglove/ws-protocol``'s FoxgloveClient (what Foxglove Studio uses,
bench/bench_bridges_client.js), ``python`` speaks ``foxglove.sdk.v1`` over ``websockets``. Each
client gets a run of the publisher of its own, beside robomodel's subscriber.

Run: ``.venv/bin/python bench/bench_bridges.py [--seconds 5] [--clients node,python]
[--bridge process|in-publisher]``.

``--bridge in-publisher`` runs the bridge in the publisher's process, on its bus, as ``robomodel
launch`` runs its built-in nodes (the simulation with its cameras, foxglove_bridge) in one
process: the bridge then has each message from the publisher's own Zenoh session rather than
over the loopback, and the CPU printed is that process's, publisher and bridge together.

Every message carries ``time.monotonic_ns()`` (CLOCK_MONOTONIC, one clock for every process of
a Linux machine) in ``header.stamp``; each receiver subtracts it on arrival. Printed per topic:
the messages published, received by each side, each side's p50 and p90 latency [ms], and the
client's p50 over robomodel's; and per client, the bridge process's CPU time (user + system,
every thread) while the publisher ran, per message it forwarded.

``--quickack`` makes the Python client acknowledge every TCP segment at once (Linux
``TCP_QUICKACK``): if the latency then drops, the rest was the server's small writes waiting
for the client's delayed acknowledgements (Nagle's algorithm), not the bridge's own time.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import statistics
import struct
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
NODE_MODULES = ROOT / ".node" / "node_modules"
TOPICS = {"/joint_states": 1000.0, "/camera/image": 30.0}
_STAMP = struct.Struct("<iI")  # CDR: 4-byte encapsulation header, then header.stamp


def _stamp(ns: int) -> Any:
    from robomodel.runtime.msg import Time

    return Time(ns // 1_000_000_000, ns % 1_000_000_000)


def messages() -> dict[str, Any]:
    """Topic -> the message published on it: a 32-joint JointState, a 640x480 rgb8 Image."""
    from robomodel.runtime.msg import get_message_type

    joint_state = get_message_type("sensor_msgs/msg/JointState")
    image_type = get_message_type("sensor_msgs/msg/Image")
    names = [f"joint_{i}" for i in range(32)]
    return {
        "/joint_states": joint_state(name=names, position=[0.1] * 32, velocity=[0.0] * 32),
        "/camera/image": image_type(height=480, width=640, encoding="rgb8", step=640 * 3,
                                    data=bytes(640 * 480 * 3)),
    }  # fmt: skip


def paced(seconds: float, send: Callable[[str], None]) -> dict[str, int]:
    """Call ``send(topic)`` at each topic's rate (``TOPICS``) for ``seconds``; the calls made per
    topic."""
    sent = dict.fromkeys(TOPICS, 0)
    start = time.monotonic()
    next_s = dict.fromkeys(TOPICS, start)
    while time.monotonic() - start < seconds:
        now = time.monotonic()
        for topic, rate_hz in TOPICS.items():
            if now >= next_s[topic]:
                send(topic)
                sent[topic] += 1
                next_s[topic] += 1.0 / rate_hz
        time.sleep(max(0.0, min(next_s.values()) - time.monotonic()))
    return sent


def _bridge_beside(context: Any, port: int) -> Any:
    """foxglove_bridge on ``context``: in the publisher's process, as ``robomodel launch`` runs
    it beside the launch's simulation and other built-in nodes."""
    from robomodel.bridges.foxglove_bridge import FoxgloveBridge
    from robomodel.bridges.rosapi import Ros2Params
    from robomodel.description.packages import PackageIndex

    params = Ros2Params(context, lambda: sorted(context.graph(timeout_s=0.3).nodes), 1.0)
    return FoxgloveBridge(context, params, dialect="ros2", package_index=PackageIndex(),
                          port=port, log=lambda line: print(line, file=sys.stderr))  # fmt: skip


def publish(domain: int, seconds: float, bridge_port: int | None = None) -> dict[str, int]:
    from robomodel.runtime import Context

    with Context("zenoh", domain_id=domain) as context:
        bridge = None if bridge_port is None else _bridge_beside(context, bridge_port)
        done = threading.Event()  # with a bridge here, a thread spins for it, as launch does
        spinner = threading.Thread(target=context.spin, kwargs={"until": done.is_set})

        def wait(seconds: float) -> None:
            if bridge is None:
                context.spin(duration_s=seconds)
            else:
                time.sleep(seconds)

        node = context.create_node("bench_bridges_pub")
        publishers = {
            topic: (node.create_publisher(type(msg), topic), msg)
            for topic, msg in messages().items()
        }
        if bridge is not None:
            spinner.start()
            print("bridge listening", flush=True)  # the receivers start now ...
            sys.stdin.readline()  # ... and have had a second when this comes
        wait(3.0)  # the receivers find the publishers
        print("publishing", flush=True)  # the bridge's CPU is read from here ...

        def send(topic: str) -> None:
            publisher, msg = publishers[topic]
            msg.header.stamp = _stamp(time.monotonic_ns())
            publisher.publish(msg)

        sent = paced(seconds, send)
        print("published", flush=True)  # ... to here
        wait(0.5)
        if bridge is not None:
            bridge.stop()
            done.set()
            spinner.join()
    return sent


def receive_robomodel(domain: int, seconds: float) -> dict[str, list[float]]:
    from robomodel.runtime import Context

    latencies: dict[str, list[float]] = {t: [] for t in TOPICS}
    with Context("zenoh", domain_id=domain) as context:
        node = context.create_node("bench_bridges_sub")
        raw = context.transport.create_raw_subscription  # type: ignore[attr-defined]
        from robomodel.runtime.msg import get_message_type
        from robomodel.runtime.qos import as_qos

        for topic, kind in (("/joint_states", "sensor_msgs/msg/JointState"),
                            ("/camera/image", "sensor_msgs/msg/Image")):  # fmt: skip

            def on(payload: bytes, _: Any, topic: str = topic) -> None:
                sec, nanosec = _STAMP.unpack_from(payload, 4)
                latencies[topic].append((time.monotonic_ns() - sec * 10**9 - nanosec) / 1e6)

            raw(node.fully_qualified_name, topic, get_message_type(kind), as_qos(10), on)
        context.spin(duration_s=seconds)
    return latencies


def receive_python(port: int, seconds: float, *, quickack: bool) -> dict[str, list[float]]:
    import socket

    from websockets.exceptions import ConnectionClosed
    from websockets.sync.client import connect

    latencies: dict[str, list[float]] = {t: [] for t in TOPICS}
    by_subscription: dict[int, str] = {}
    deadline = time.monotonic() + seconds
    with connect(f"ws://127.0.0.1:{port}", subprotocols=["foxglove.sdk.v1"], max_size=None,
                 compression=None) as ws:  # fmt: skip
        while time.monotonic() < deadline:
            if quickack:  # Linux resets it after a while: set before every read
                ws.socket.setsockopt(socket.IPPROTO_TCP, socket.TCP_QUICKACK, 1)
            try:
                frame = ws.recv(timeout=0.5)
            except TimeoutError:
                continue
            except ConnectionClosed:  # the bridge ended (with its publisher, --bridge in-publisher)
                break
            if isinstance(frame, str):
                message = json.loads(frame)
                if message["op"] == "advertise":
                    wanted = [c for c in message["channels"] if c["topic"] in TOPICS]
                    subscriptions = []
                    for channel in wanted:
                        sub_id = len(by_subscription) + 1
                        by_subscription[sub_id] = channel["topic"]
                        subscriptions.append({"id": sub_id, "channelId": channel["id"]})
                    if subscriptions:
                        ws.send(json.dumps({"op": "subscribe", "subscriptions": subscriptions}))
                continue
            if frame[0] != 1:  # messageData: opcode, subscription id, log time, payload
                continue
            (sub_id,) = struct.unpack_from("<I", frame, 1)
            sec, nanosec = _STAMP.unpack_from(frame, 13 + 4)
            latencies[by_subscription[sub_id]].append(
                (time.monotonic_ns() - sec * 10**9 - nanosec) / 1e6
            )
    return latencies


def _role(args: argparse.Namespace) -> None:
    if args.role == "publish":
        result: Any = publish(args.domain_id, args.seconds,
                              args.port if args.bridge == "in-publisher" else None)  # fmt: skip
    elif args.role == "robomodel":
        result = receive_robomodel(args.domain_id, args.seconds + 15.0)
    else:
        result = receive_python(args.port, args.seconds + 15.0, quickack=args.quickack)
    print(json.dumps(result))


def _percentile(values: list[float], q: float) -> float:
    return statistics.quantiles(values, n=100)[int(q) - 1] if len(values) > 1 else float("nan")


def _cpu_s(pid: int) -> float:
    """CPU time [s] (user + system, every thread) that process ``pid`` has used (Linux)."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _node_client(port: int, seconds: float) -> list[str]:
    node = shutil.which("node")
    if node is None or not (NODE_MODULES / "@foxglove" / "ws-protocol").is_dir():
        sys.exit("bench_bridges: the node client needs node and @foxglove/ws-protocol in "
                 f"{NODE_MODULES} (tools/system-deps test installs them); or --clients python")  # fmt: skip
    return [node, str(ROOT / "bench" / "bench_bridges_client.js"), f"ws://127.0.0.1:{port}",
            str(seconds), *TOPICS]  # fmt: skip


def _phase(
    args: argparse.Namespace, client: str, bridge_pid: int | None, env: dict[str, str]
) -> Any:
    """One run of the publisher with robomodel's subscriber and ``client`` receiving; the CPU
    is read of ``bridge_pid``, or of the publisher's process when the bridge is in it (None)."""
    me = [sys.executable, __file__, "--seconds", str(args.seconds), "--domain-id",
          str(args.domain_id), "--port", str(args.port)]  # fmt: skip
    if args.quickack:
        me.append("--quickack")
    listen_s = args.seconds + 15.0
    commands = {
        "robomodel": [*me, "--role", "robomodel"],
        client: _node_client(args.port, listen_s) if client == "node" else [*me, "--role", client],
    }
    beside = args.bridge == "in-publisher"
    publisher = None
    if beside:  # the bridge is in the publisher: it listens before the receivers start
        publisher = subprocess.Popen([*me, "--bridge", args.bridge, "--role", "publish"], env=env,
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)  # fmt: skip
        assert publisher.stdout is not None and publisher.stdin is not None
        if publisher.stdout.readline().strip() != "bridge listening":
            sys.exit("bench_bridges: the publisher's bridge did not start")
    receivers = {
        side: subprocess.Popen(command, env=env, stdout=subprocess.PIPE, text=True)
        for side, command in commands.items()
    }
    time.sleep(1.0)  # the receivers subscribe before the publisher's first message
    if publisher is None:
        publisher = subprocess.Popen([*me, "--role", "publish"], env=env,
                                     stdout=subprocess.PIPE, text=True)  # fmt: skip
    else:
        assert publisher.stdin is not None
        publisher.stdin.write("go\n")
        publisher.stdin.flush()
    assert publisher.stdout is not None
    cpu_s = 0.0
    for line in publisher.stdout:
        if line.strip() in ("publishing", "published"):
            cpu_s = _cpu_s(bridge_pid or publisher.pid) - cpu_s
        else:
            sent = json.loads(line)
    if publisher.wait() != 0:
        sys.exit("bench_bridges: the publisher failed")
    got = {side: json.loads(proc.communicate()[0]) for side, proc in receivers.items()}
    return sent, got, cpu_s


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=5.0)
    parser.add_argument("--domain-id", type=int, default=120)
    parser.add_argument("--port", type=int, default=18765)
    parser.add_argument("--role", choices=("publish", "robomodel", "python"))
    parser.add_argument(
        "--bridge",
        choices=("process", "in-publisher"),
        default="process",
        help="where foxglove_bridge runs: a process of its own (robomodel run foxglove_bridge "
        "foxglove_bridge), or in the publisher's, as robomodel launch runs it beside the "
        "launch's simulation",
    )
    parser.add_argument(
        "--clients",
        default="node,python",
        help="the Foxglove clients measured, one run of the publisher each: node "
        "(@foxglove/ws-protocol's FoxgloveClient) and python (websockets)",
    )
    parser.add_argument(
        "--quickack",
        action="store_true",
        help="the Python Foxglove client acknowledges every TCP segment at once",
    )
    args = parser.parse_args()
    if args.role:
        _role(args)
        return
    clients = [c for c in args.clients.split(",") if c]
    unknown = sorted(set(clients) - {"node", "python"})
    if unknown or not clients:
        parser.error(f"--clients: unknown {', '.join(unknown) or 'none'}; they are node, python")
    load = os.getloadavg()
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"),
           "ROBOMODEL_NODE_MODULES": str(NODE_MODULES)}  # fmt: skip
    phases = {}
    if args.bridge == "in-publisher":
        for client in clients:
            phases[client] = _phase(args, client, None, env)
    else:
        bridge = subprocess.Popen(
            [sys.executable, "-m", "robomodel.cli.main", "run", "--domain-id",
             str(args.domain_id), "foxglove_bridge", "foxglove_bridge", "--ros-args", "-p",
             f"port:={args.port}"],
            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
            start_new_session=True,
        )  # fmt: skip
        try:
            assert bridge.stdout is not None
            for line in bridge.stdout:
                if "listening at" in line:
                    break
            for client in clients:
                phases[client] = _phase(args, client, bridge.pid, env)
        finally:
            os.killpg(bridge.pid, signal.SIGINT)
            bridge.wait(30)
    print(f"foxglove_bridge ({args.bridge}) vs robomodel's subscriber, {args.seconds:g} s a client "
          f"(latency [ms]); "
          f"load average before {load[0]:.2f} (1 min), {load[1]:.2f} (5 min)")  # fmt: skip
    print(f"{'topic':<16}{'sent':>7}{'side':>11}{'received':>10}{'p50':>9}{'p90':>9}{'ratio':>8}")
    for client, (sent, got, cpu_s) in phases.items():
        for topic in TOPICS:
            own = _percentile(got["robomodel"][topic], 50)
            for side in ("robomodel", client):
                values = got[side][topic]
                p50 = _percentile(values, 50)
                ratio = f"{p50 / own:>8.2f}" if side == client else ""
                print(f"{topic:<16}{sent[topic]:>7}{side:>11}{len(values):>10}"
                      f"{p50:>9.2f}{_percentile(values, 90):>9.2f}{ratio}")  # fmt: skip
        forwarded = sum(len(got[client][t]) for t in TOPICS)
        whose = "bridge" if args.bridge == "process" else "publisher's process with the bridge"
        print(
            f"{whose} CPU while publishing to the {client} client: {cpu_s * 1e3:.0f} ms for "
            f"{forwarded} messages, {cpu_s / max(1, forwarded) * 1e6:.0f} us a message "
            f"({cpu_s / args.seconds * 100:.0f}% of a core)"
        )


if __name__ == "__main__":
    main()
