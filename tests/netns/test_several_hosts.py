"""Several machines, checked on one: each "host" is a network namespace of its
own, with its own loopback and one private address, joined to a "router host" by a veth pair
(10.200.1.0/24 and 10.200.2.0/24, inside these namespaces only; the router host forwards
between them). Nothing a test runs can then reach another through 127.0.0.1: every message
crosses the addresses given on the command line.

- Zenoh: ``robomodel router --listen tcp/<address>:7447`` on the router host, ``publish-state``
  and ``control run`` on host A and ``tf ... --once`` and ``control list-controllers`` on host
  B, each with ``--connect`` to the router's address on its side and ``--listen`` on its own
  address (rmw_zenoh's peers link directly once the router has introduced them).
- ROS 1: ``robomodel master`` on the router host, ``publish-state --bus ros1`` on A and Debian's
  ``rostopic echo -n1 /tf`` on B, with ``ROS_MASTER_URI`` and ``ROS_IP`` (each host's own
  address, which the TCPROS connection from B to A uses).

Needs root and iproute2; skipped with one line where namespaces cannot be created.
"""

from __future__ import annotations

import contextlib
import itertools
import os
import shutil
import signal
import subprocess
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, ROBOMODEL
from tests.timing import scaled

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"
ARM = EXAMPLES / "two_link_arm/urdf/two_link_arm.urdf.xacro"
ARM_CONTROLLERS = EXAMPLES / "two_link_arm/config/position_controllers.yaml"
ROUTER_A, HOST_A = "10.200.1.1", "10.200.1.2"
ROUTER_B, HOST_B = "10.200.2.1", "10.200.2.2"
_COUNT = itertools.count()


def _ip(*args: str) -> None:
    subprocess.run(["ip", *args], check=True, capture_output=True, text=True, timeout=scaled(30))


@dataclass
class Hosts:
    """Three namespaces (``r``, ``a``, ``b``) and the processes started in them."""

    names: dict[str, str]
    env: dict[str, str]
    started: list[subprocess.Popen[str]] = field(default_factory=list)

    def start(self, host: str, *cmd: str, **env: str) -> subprocess.Popen[str]:
        process = subprocess.Popen(
            ["ip", "netns", "exec", self.names[host], *cmd],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
            env={**self.env, **env},
        )  # fmt: skip
        self.started.append(process)
        return process

    def run(
        self, host: str, *cmd: str, timeout: float = 60, **env: str
    ) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            ["ip", "netns", "exec", self.names[host], *cmd],
            capture_output=True, text=True, timeout=scaled(timeout), env={**self.env, **env},
        )  # fmt: skip


def _create(names: dict[str, str]) -> None:
    for name in names.values():
        _ip("netns", "add", name)
        _ip("-n", name, "link", "set", "lo", "up")
    r = names["r"]
    for side, router_address, address in (("a", ROUTER_A, HOST_A), ("b", ROUTER_B, HOST_B)):
        host = names[side]
        _ip("link", "add", f"{host}v", "netns", host, "type", "veth", "peer", "name",
            f"{host}r", "netns", r)  # fmt: skip
        _ip("-n", host, "addr", "add", f"{address}/24", "dev", f"{host}v")
        _ip("-n", r, "addr", "add", f"{router_address}/24", "dev", f"{host}r")
        _ip("-n", host, "link", "set", f"{host}v", "up")
        _ip("-n", r, "link", "set", f"{host}r", "up")
        _ip("-n", host, "route", "add", "default", "via", router_address)
    _ip("netns", "exec", r, "sysctl", "-qw", "net.ipv4.ip_forward=1")


def _end_all(hosts: Hosts) -> None:
    for process in hosts.started:
        if process.poll() is None:
            process.send_signal(signal.SIGINT)
    for process in hosts.started:
        try:
            process.communicate(timeout=scaled(10))
        except subprocess.TimeoutExpired:
            process.kill()
            process.communicate()
    for name in hosts.names.values():  # anything still in a namespace (a detached router)
        pids = subprocess.run(["ip", "netns", "pids", name], capture_output=True, text=True)
        for pid in pids.stdout.split():
            with contextlib.suppress(ProcessLookupError, ValueError):
                os.kill(int(pid), signal.SIGKILL)


@pytest.fixture
def hosts(tmp_path: Path) -> Iterator[Hosts]:
    if os.geteuid() != 0 or shutil.which("ip") is None:
        pytest.skip("network namespaces need root and iproute2's ip")
    tag = f"rm{os.getpid() % 100000}{next(_COUNT)}"
    names = {role: f"{tag}{role}" for role in ("r", "a", "b")}
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ZENOH_", "ROS_"))}
    env["XDG_RUNTIME_DIR"] = str(tmp_path)
    made = Hosts(names, env)
    try:
        try:
            _create(names)
        except (subprocess.CalledProcessError, OSError) as exc:
            detail = exc.stderr.strip() if isinstance(exc, subprocess.CalledProcessError) else exc
            pytest.skip(f"cannot create network namespaces here: {detail}")
        yield made
    finally:
        _end_all(made)
        for name in names.values():
            subprocess.run(["ip", "netns", "del", name], capture_output=True)


def _first_line_with(process: subprocess.Popen[str], text: str) -> str:
    assert process.stderr is not None
    for line in process.stderr:
        if text in line:
            return line
    raise AssertionError(f"the process ended without printing {text!r}")


def test_zenoh_graph_across_hosts(hosts: Hosts) -> None:
    router = hosts.start("r", *ROBOMODEL, "router", "--listen", f"tcp/{ROUTER_A}:7447",
                         "--listen", f"tcp/{ROUTER_B}:7447")  # fmt: skip
    _first_line_with(router, "Started Zenoh router")
    # as rmw_zenoh's peers: the router introduces them, then they link directly, so each
    # listens on its host's address too (a loopback-only peer cannot be reached from B)
    to_a = ("--connect", f"tcp/{ROUTER_A}:7447", "--listen", f"tcp/{HOST_A}:0")
    to_b = ("--connect", f"tcp/{ROUTER_B}:7447", "--listen", f"tcp/{HOST_B}:0")
    state = hosts.start("a", *ROBOMODEL, "publish-state", str(PLANAR), *to_a)
    _first_line_with(state, "publishing robot")
    within = f"{scaled(30):.1f}"
    tf = hosts.run(
        "b", *ROBOMODEL, "tf", "base_link", "gripper", "--once", "--timeout", within, *to_b
    )
    assert tf.returncode == 0, tf.stderr
    assert tf.stdout.startswith("At time ") and "- Translation: [" in tf.stdout
    control = hosts.start("a", *ROBOMODEL, "control", "run", str(ARM), "--controllers",
                          str(ARM_CONTROLLERS), "--no-view", *to_a)  # fmt: skip
    _first_line_with(control, "controller manager")
    deadline = time.monotonic() + scaled(60)
    listed = hosts.run("b", *ROBOMODEL, "control", "list-controllers", *to_b)
    while "joint1_position_controller" not in listed.stdout and time.monotonic() < deadline:
        listed = hosts.run("b", *ROBOMODEL, "control", "list-controllers", *to_b)
    assert listed.returncode == 0, listed.stderr
    assert "joint1_position_controller" in listed.stdout and "active" in listed.stdout


def test_ros1_master_across_hosts(hosts: Hosts) -> None:
    if shutil.which("rostopic") is None:
        pytest.skip("Debian's rostopic is not installed (tools/system-deps test)")
    master_uri = f"http://{ROUTER_A}:11311/"
    master = hosts.start("r", *ROBOMODEL, "master", ROS_IP=ROUTER_A, ROS_MASTER_URI=master_uri)
    deadline = time.monotonic() + scaled(30)
    while hosts.run("b", "rostopic", "list", timeout=30, ROS_MASTER_URI=master_uri,
                    ROS_IP=HOST_B).returncode != 0:  # fmt: skip
        assert master.poll() is None and time.monotonic() < deadline, "the master did not answer"
        time.sleep(0.2)
    state = hosts.start("a", *ROBOMODEL, "publish-state", str(PLANAR), "--bus", "ros1",
                        ROS_MASTER_URI=master_uri, ROS_IP=HOST_A)  # fmt: skip
    _first_line_with(state, "publishing robot")
    echo = hosts.run("b", "rostopic", "echo", "-n1", "/tf", timeout=60,
                     ROS_MASTER_URI=master_uri, ROS_IP=HOST_B)  # fmt: skip
    assert echo.returncode == 0, echo.stderr
    assert "transforms:" in echo.stdout and 'child_frame_id: "link_1"' in echo.stdout
