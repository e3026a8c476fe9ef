"""Long-running commands say which graph they joined (issue 32: master, domain and router are
shared machine-wide by default, so a user on a shared machine must see which one they are in)."""

from __future__ import annotations

import os
import subprocess

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
    ros1.until(lambda: ros1.run("/usr/bin/rosparam", "get", "/run_id").returncode == 0, "master")
    done = ros1.run(*ROBOMODEL, "publish-state", ARM, "--duration", "0.5", timeout=scaled(60))
    assert done.returncode == 0, done.stderr
    assert f"bus: ros1, master {ros1.uri}" in done.stderr.splitlines()[0]
