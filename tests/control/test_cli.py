"""``robomodel control``: run on every example, and the verbs across processes over Zenoh."""

from __future__ import annotations

import subprocess
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
import yaml

from tests.conftest import EXAMPLES, ROBOMODEL, end_process, past_the_bus_line, unique_domain
from tests.timing import scaled

RUNS = [
    ("rrbot_description/urdf/rrbot.xacro", "rrbot_description/config/rrbot_control.yaml"),
    ("ur5_description/urdf/ur5.urdf.xacro", "ur5_description/config/ur5_controllers.yaml"),
    (
        "simplebot_description/urdf/simplebot.urdf.xacro",
        "simplebot_description/config/simplebot_controllers.yaml",
    ),
    ("two_link_arm/urdf/two_link_arm.urdf.xacro", "two_link_arm/config/position_controllers.yaml"),
]


@pytest.mark.parametrize(("urdf", "config"), RUNS, ids=[r[0].split("/")[0] for r in RUNS])
def test_control_run_every_example(urdf: str, config: str, cli: Callable[..., object]) -> None:
    result = cli(
        "control",
        "run",
        str(EXAMPLES / urdf),
        "--controllers",
        str(EXAMPLES / config),
        "--no-view",
        "--bus",
        "inproc",
        "--duration",
        "0.3",
    )
    assert result.code == 0, result.err  # type: ignore[attr-defined]
    assert "active" in result.err  # type: ignore[attr-defined]


def test_control_run_without_no_view_continues_headless(cli: Callable[..., object]) -> None:
    urdf, config = RUNS[3]
    result = cli(
        "control",
        "run",
        str(EXAMPLES / urdf),
        "--controllers",
        str(EXAMPLES / config),
        "--bus",
        "inproc",
        "--duration",
        "0.1",
    )
    assert result.code == 0  # type: ignore[attr-defined]


def test_bad_controller_file_reports_file_line(tmp_path: Path, cli: Callable[..., object]) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("joint_state_controller:\n  type: joint_state_controler/JointStateController\n")
    result = cli(
        "control",
        "run",
        str(EXAMPLES / RUNS[0][0]),
        "--controllers",
        str(bad),
        "--no-view",
        "--bus",
        "inproc",
        "--duration",
        "0.1",
    )
    assert result.code == 2  # type: ignore[attr-defined]
    assert f"{bad}:2:3" in result.err and "did you mean" in result.err  # type: ignore[attr-defined]


def _domain() -> str:
    return unique_domain()


def _cli(*args: str, timeout: float = 20) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*ROBOMODEL, *args], capture_output=True, text=True, timeout=scaled(timeout)
    )


@pytest.fixture
def rrbot_run() -> Iterator[str]:
    domain = _domain()
    proc = subprocess.Popen(
        [
            *ROBOMODEL,
            "control",
            "run",
            str(EXAMPLES / RUNS[0][0]),
            "--controllers",
            str(EXAMPLES / RUNS[0][1]),
            "--no-view",
            "--domain-id",
            domain,
            "--duration",
            str(scaled(60)),  # ended by the test; a bound if it is not
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert proc.stderr is not None
    line = past_the_bus_line(proc.stderr)
    assert "controller manager" in line, line + proc.stderr.read()
    yield domain
    end_process(proc)


def _joint1(domain: str) -> float:
    echo = _cli("topic", "echo", "/joint_states", "--once", "--domain-id", domain)
    assert echo.returncode == 0, echo.stderr
    return float(yaml.safe_load(echo.stdout.split("---")[0])["position"][0])


def test_seed_000_workflow_over_zenoh(rrbot_run: str) -> None:
    domain = rrbot_run
    listed = _cli("control", "list-controllers", "--domain-id", domain)
    assert listed.returncode == 0, listed.stderr
    rows = {tuple(line.split()) for line in listed.stdout.splitlines()}
    assert {  # the types as the YAML names them
        ("joint_state_controller", "joint_state_controller/JointStateController", "active"),
        ("joint1_position_controller", "effort_controllers/JointPositionController", "active"),
    } <= rows
    assert abs(_joint1(domain)) < 0.05
    pub = _cli(
        "topic",
        "pub",
        "/joint1_position_controller/command",
        "std_msgs/msg/Float64",
        "data: 1.5",
        "--once",
        "--domain-id",
        domain,
    )
    assert pub.returncode == 0, pub.stderr
    deadline = time.monotonic() + scaled(15)
    position = 0.0
    while time.monotonic() < deadline:
        position = _joint1(domain)
        if abs(position - 1.6) < 0.2:
            break
        time.sleep(0.5)
    assert position == pytest.approx(1.6, abs=0.2)  # PD (no i_clamp) sags under gravity
    sw = _cli(
        "control", "switch", "--deactivate", "joint1_position_controller", "--domain-id", domain
    )
    assert sw.returncode == 0, sw.stderr
    hw = _cli("control", "list-hardware-interfaces", "--domain-id", domain)
    assert "\tjoint1/effort [available] [unclaimed]" in hw.stdout
    assert "\tjoint2/effort [available] [claimed]" in hw.stdout
    assert (
        _cli("control", "unload", "joint1_position_controller", "--domain-id", domain).returncode
        == 0
    )
    load = _cli(
        "control",
        "load",
        "joint1_position_controller",
        "--set-state",
        "active",
        "--domain-id",
        domain,
    )
    assert load.returncode == 0, load.stderr
    bad = _cli("control", "switch", "--activate", "nope", "--strict", "--domain-id", domain)
    assert bad.returncode == 2 and "unknown controller 'nope'" in bad.stderr
    listed = _cli("control", "list-controllers", "--domain-id", domain)
    assert listed.stdout.count("active") == 3
    comps = _cli("control", "list-hardware-components", "--domain-id", domain)
    assert "\tname: rrbot_transmissions" in comps.stdout
    assert "plugin name: mock_components/GenericSystem" in comps.stdout
    types = _cli("control", "list-controller-types", "--domain-id", domain)
    assert "diff_drive_controller/DiffDriveController" in types.stdout.splitlines()


def test_seed_003_load_with_set_state_start_over_zenoh() -> None:
    domain = unique_domain()
    urdf, config = RUNS[3]
    proc = subprocess.Popen(
        [
            *ROBOMODEL,
            "control",
            "run",
            str(EXAMPLES / urdf),
            "--controllers",
            str(EXAMPLES / config),
            "--no-view",
            "--no-spawn",
            "--domain-id",
            domain,
            "--duration",
            str(scaled(60)),  # ended by the test; a bound if it is not
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        assert proc.stderr is not None and "controller manager" in past_the_bus_line(proc.stderr)
        for name in ("joint_state_broadcaster", "joint1_position_controller"):
            load = _cli("control", "load", "--set-state", "start", name, "--domain-id", domain)
            assert load.returncode == 0, load.stderr
        listed = _cli("control", "list-controllers", "--domain-id", domain)
        assert listed.stdout.count(" active") == 2, listed.stdout
        pub = _cli(
            "topic",
            "pub",
            "/joint1_position_controller/commands",
            "std_msgs/msg/Float64MultiArray",
            "data: [1.0]",
            "--once",
            "--domain-id",
            domain,
        )
        assert pub.returncode == 0, pub.stderr
        deadline = time.monotonic() + scaled(10)
        while time.monotonic() < deadline and abs(_joint1(domain) - 1.0) > 1e-9:
            time.sleep(0.3)
        assert _joint1(domain) == 1.0
        _lifecycle_verbs(domain, "joint1_position_controller")
    finally:
        end_process(proc)


def test_controller_parameter_error_points_at_the_yaml(
    tmp_path: Path, cli: Callable[..., object]
) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text(
        "controller_manager:\n  ros__parameters:\n    fwd:\n"
        "      type: forward_command_controller/ForwardCommandController\n"
        "fwd:\n  ros__parameters:\n    joints: [joint1]\n"
    )
    result = cli(
        "control",
        "run",
        str(EXAMPLES / RUNS[3][0]),
        "--controllers",
        str(bad),
        "--no-view",
        "--bus",
        "inproc",
        "--duration",
        "0.1",
    )
    assert result.code == 2  # type: ignore[attr-defined]
    assert f"{bad}:4:7: controller 'fwd': 'interface_name' is required" in result.err  # type: ignore[attr-defined]


def _lifecycle_verbs(domain: str, name: str) -> None:
    """cleanup, configure and unload walk the controller through its states, each saying so in
    ros2controlcli's words (cleanup_controller.py: "Successfully cleaned up controller X")."""

    def state() -> str:
        listed = _cli("control", "list-controllers", "--domain-id", domain)
        rows = {line.split()[0]: line.split()[-1] for line in listed.stdout.splitlines()}
        return rows.get(name, "gone")

    switch = _cli("control", "switch", "--deactivate", name, "--domain-id", domain)
    assert switch.returncode == 0, switch.stderr
    assert state() == "inactive"
    for verb, said, after in (
        ("cleanup", "cleaned up", "unconfigured"),
        ("configure", "configured", "inactive"),
        ("unload", "unloaded", "gone"),
    ):
        done = _cli("control", verb, name, "--domain-id", domain)
        assert done.returncode == 0, done.stderr
        assert done.stdout == f"Successfully {said} controller {name}\n"
        assert state() == after, verb
    again = _cli("control", "configure", name, "--domain-id", domain)
    assert again.returncode == 2 and again.stderr.count("\n") == 1, again.stderr
    assert "the controller manager's log says why" in again.stderr
    assert "is `robomodel control run` running" not in again.stderr  # it answered: it runs
