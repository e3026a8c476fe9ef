"""``robomodel bag play`` reproduces the recorded /joint_states sequence, as ``topic echo`` sees
it, with the recorded timing."""

from __future__ import annotations

import subprocess
import time
from pathlib import Path

from robomodel.bag import open_bag
from robomodel.runtime import Context
from robomodel.runtime.msg import JointState, deserialize, message_to_yaml
from tests.conftest import ROBOMODEL, unique_domain
from tests.timing import scaled, wait_until

from .conftest import Talker, run_cli, stop


def _wait_subscribed(domain: str, topic: str, timeout_s: float = 15) -> None:
    with Context("zenoh", domain_id=int(domain)) as context:

        def subscribed() -> bool:
            info = context.graph(timeout_s=scaled(0.3)).topics.get(topic)
            return info is not None and bool(info.subscribers)

        wait_until(subscribed, timeout_s, what=f"a subscriber on {topic}", interval_s=0.1)


def test_play_reproduces_the_joint_states_seen_by_echo(tmp_path: Path) -> None:
    talker = Talker(tmp_path, period_s=0.02)
    out = tmp_path / "run"
    try:
        rec = run_cli(
            "bag", "record", "/joint_states", "/robot_description", "-o", str(out),
            "--duration", f"{scaled(2):.1f}", "--domain-id", talker.domain,
        )  # fmt: skip
    finally:
        stop(talker.proc)
    assert rec.returncode == 0, rec.stderr
    bag = open_bag(out)
    recorded = [m for m in bag.messages() if m.topic == "/joint_states"]
    expected = [message_to_yaml(deserialize(m.data, JointState)) for m in recorded]
    assert len(expected) > 30
    span_s = (recorded[-1].log_time_ns - recorded[0].log_time_ns) / 1e9

    domain = unique_domain()  # a bus where the talker is not
    echo = subprocess.Popen(
        [*ROBOMODEL, "topic", "echo", "/joint_states", "sensor_msgs/msg/JointState",
         "--count", str(len(expected)), "--timeout", f"{scaled(30):.1f}", "--domain-id", domain,
         "--qos-history", "keep_all"],  # a busy machine may hold the printer back
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        _wait_subscribed(domain, "/joint_states")
        started = time.monotonic()
        play = run_cli("bag", "play", str(out), "--domain-id", domain)
        elapsed = time.monotonic() - started
        assert play.returncode == 0, play.stderr
        seen, err = echo.communicate(timeout=scaled(30))
    finally:
        stop(echo)
    assert echo.returncode == 0, err
    docs = [d for d in seen.split("---\n") if d.strip()]
    assert docs == expected  # every message, in order, with the recorded contents
    assert elapsed >= 0.9 * span_s  # recorded spacing kept, not published as fast as possible
    assert f"played {len(expected) + 1} messages" in play.stderr  # and /robot_description
