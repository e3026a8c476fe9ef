"""Bag benchmark: ``robomodel bag record`` of talos' /tf at 1 kHz over Zenoh on loopback.

Run: ``.venv/bin/python bench/bench_bag.py [--seconds 10] [--rate 1000] [--rounds 3]
[--ros1]``.

A publisher process sends a TFMessage with one transform per movable joint of talos_full_v2
(the /tf that robot_state_publisher sends for it) at ``--rate``; ``robomodel bag record /tf``
runs in another process for the same time. Printed per round: messages sent and recorded,
recorded messages/s and MB/s (bytes of the bag over the recording time), and the CPU of each
process (as a share of one core, from /proc).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import example_robot_data, paced_sends

ROBOT = "talos_data/robots/talos_full_v2.urdf"
ROBOMODEL = [sys.executable, "-m", "robomodel.cli.main"]


def _cpu_s(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _tf_message() -> object:
    import robomodel
    from robomodel.runtime.msg import Header, TFMessage, Transform, TransformStamped

    robot = robomodel.load(example_robot_data(ROBOT).read_text())
    movable = [j for j in robot.joints if j.type.value != "fixed"]
    return TFMessage(
        [TransformStamped(Header(frame_id=j.parent), j.child, Transform()) for j in movable]
    )


def role_publisher(domain: int, seconds: float, rate: float) -> None:
    from robomodel.runtime import Context
    from robomodel.runtime.msg import TFMessage, Time

    msg = _tf_message()
    assert isinstance(msg, TFMessage)
    with Context("zenoh", domain_id=domain) as ctx:
        pub = ctx.create_node("tf_source").create_publisher(TFMessage, "/tf", 100)
        print(f"ready {len(msg.transforms)}", flush=True)
        sys.stdin.readline()  # the recorder has subscribed

        def send(_: int) -> None:
            stamp = Time.from_seconds(time.time())
            for t in msg.transforms:
                t.header.stamp = stamp
            pub.publish(msg)

        sent, elapsed = paced_sends(seconds, rate, send)
        ctx.spin(duration_s=0.3)
        print(json.dumps({"sent": sent, "elapsed_s": elapsed}), flush=True)


def _round(seconds: float, rate: float, domain: int, ros1: bool) -> dict[str, float]:
    work = Path(tempfile.mkdtemp(prefix="bench_bag_"))
    out = work / ("tf.bag" if ros1 else "tf")
    publisher = subprocess.Popen(
        [sys.executable, __file__, "--role", "publisher", "--domain", str(domain),
         "--seconds", str(seconds), "--rate", str(rate)],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
    )  # fmt: skip
    assert publisher.stdout is not None and publisher.stdin is not None
    transforms = int(publisher.stdout.readline().split()[1])
    target = ["--ros1", str(out)] if ros1 else ["-o", str(out)]
    recorder = subprocess.Popen(
        [*ROBOMODEL, "bag", "record", "/tf", *target, "--no-progress",
         "--duration", str(seconds + 4), "--domain-id", str(domain)],
        stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    time.sleep(2.5)  # the recorder finds /tf and subscribes
    rec_cpu0, pub_cpu0 = _cpu_s(recorder.pid), _cpu_s(publisher.pid)
    publisher.stdin.write("go\n")
    publisher.stdin.flush()
    sent = json.loads(publisher.stdout.readline())
    rec_cpu1, pub_cpu1 = _cpu_s(recorder.pid), _cpu_s(publisher.pid)
    publisher.wait()
    _, err = recorder.communicate()
    recorded = int(err.split("recorded ")[1].split()[0])
    size = sum(p.stat().st_size for p in ([out] if ros1 else list(out.glob("*.mcap"))))
    shutil.rmtree(work)
    elapsed = sent["elapsed_s"]
    return {
        "transforms": transforms,
        "sent": sent["sent"],
        "recorded": recorded,
        "msgs_per_s": recorded / elapsed,
        "MB_per_s": size / elapsed / 1e6,
        "recorder_cpu": (rec_cpu1 - rec_cpu0) / elapsed,
        "publisher_cpu": (pub_cpu1 - pub_cpu0) / elapsed,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--role", default="main")
    parser.add_argument("--domain", type=int, default=201)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--rate", type=float, default=1000.0)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--ros1", action="store_true", help="record a ROS 1 .bag instead")
    args = parser.parse_args()
    if args.role == "publisher":
        role_publisher(args.domain, args.seconds, args.rate)
        return
    for index in range(args.rounds):
        r = _round(args.seconds, args.rate, args.domain + index, args.ros1)
        print(
            f"round {index + 1}: {r['transforms']:.0f} transforms per message; sent "
            f"{r['sent']:.0f}, recorded {r['recorded']:.0f}; {r['msgs_per_s']:.0f} msg/s, "
            f"{r['MB_per_s']:.2f} MB/s; CPU recorder {100 * r['recorder_cpu']:.0f} %, "
            f"publisher {100 * r['publisher_cpu']:.0f} %",
            flush=True,
        )


if __name__ == "__main__":
    main()
