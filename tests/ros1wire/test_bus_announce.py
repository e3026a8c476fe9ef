"""Long-running commands say which graph they joined: master, domain and router
are shared machine-wide by default, so a user on a shared machine must see which one they are in."""

from __future__ import annotations

import os
import select
import signal
import subprocess

import pytest

from tests.conftest import EXAMPLES, ROBOMODEL, unique_domain
from tests.ros1wire.conftest import Ros1
from tests.timing import scaled

ARM = str(EXAMPLES / "gripper_description/urdf/planar_3dof.urdf")


def test_publish_state_names_its_zenoh_domain_and_router() -> None:
    domain = unique_domain()
    env = dict(os.environ, ROS_DOMAIN_ID=domain)
    env.pop("ROS_MASTER_URI", None)
    done = subprocess.run(
        [*ROBOMODEL, "publish-state", ARM, "--duration", "0.5"],
        capture_output=True, text=True, env=env, timeout=scaled(60),
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    first = done.stderr.splitlines()[0]
    assert first.startswith("robomodel publish-state: bus: zenoh (rmw_zenoh), domain " + domain)
    assert "router tcp/localhost:7447" in first


def test_publish_state_names_its_ros1_master(ros1: Ros1) -> None:
    ros1.robomodel("master", "-p", str(ros1.port))
    ros1.wait_for_master()
    done = ros1.run(*ROBOMODEL, "publish-state", ARM, "--duration", "0.5", timeout=scaled(60))
    assert done.returncode == 0, done.stderr
    assert f"bus: ros1, master {ros1.uri}" in done.stderr.splitlines()[0]


_UNTIL_CTRL_C = [
    ("topic", "echo", "/chatter", "std_msgs/msg/String"),
    ("topic", "hz", "/chatter"),
    ("topic", "pub", "-r", "2", "/chatter", "std_msgs/msg/String", "data: hi"),
    ("tf", "base_link", "gripper"),
]


def _first_stderr_line(argv: tuple[str, ...], env: dict[str, str]) -> tuple[str, str]:
    """The first line a command writes on stderr (waited for), and all it wrote by Ctrl-C."""
    proc = subprocess.Popen(
        [*ROBOMODEL, *argv], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
        env=env, start_new_session=True,
    )  # fmt: skip
    assert proc.stderr is not None
    try:
        ready, _, _ = select.select([proc.stderr], [], [], scaled(60))
        first = proc.stderr.readline() if ready else ""
    finally:
        os.killpg(proc.pid, signal.SIGINT)
        rest = proc.communicate(timeout=scaled(30))[1]
    return first, first + rest


@pytest.mark.parametrize("argv", _UNTIL_CTRL_C, ids=" ".join)
def test_commands_that_run_until_ctrl_c_name_their_graph_first(argv: tuple[str, ...]) -> None:
    domain = unique_domain()
    env = dict(os.environ, ROS_DOMAIN_ID=domain)
    env.pop("ROS_MASTER_URI", None)
    verb = " ".join(argv[:2]) if argv[0] == "topic" else argv[0]
    first, _ = _first_stderr_line(argv, env)
    assert first.startswith(f"robomodel {verb}: bus: zenoh (rmw_zenoh), domain {domain} "), first


def test_a_command_that_ends_by_itself_prints_no_graph_line() -> None:
    env = dict(os.environ, ROS_DOMAIN_ID=unique_domain())
    env.pop("ROS_MASTER_URI", None)
    done = subprocess.run(
        [*ROBOMODEL, "tf", "base_link", "gripper", "--once", "--timeout", "1"],
        capture_output=True, text=True, env=env, timeout=scaled(60),
    )  # fmt: skip
    assert done.returncode != 0 and "bus:" not in done.stderr, done.stderr
