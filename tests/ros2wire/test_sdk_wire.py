"""robomodel on rmw_zenoh's wire, checked against an independent implementation of it:
zenoh-ros2-sdk (PyPI), in a venv of its own with its own Zenoh (``make test`` creates
``.venv-ros2sdk``; ``ROBOMODEL_ROS2SDK_PYTHON`` points elsewhere).

The SDK subscribes to robomodel's /joint_states and /tf, publishes a Float64MultiArray that
moves a robomodel controller's joint, calls a robomodel node's parameter service and a
controller manager service, lists robomodel's topics with their ROS 2 types, and computes
every type hash itself; robomodel's ``topic list`` and ``topic echo`` see the SDK's publisher.
"""

from __future__ import annotations

import json
import os
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from robomodel.runtime.msg import Float64MultiArray, JointState, Message, String, TFMessage
from robomodel.runtime.msg.schema import Service
from robomodel.runtime.msg.typehash import type_hash
from robomodel.runtime.msg.types import controller_manager_msgs, gazebo_msgs, rcl_interfaces
from robomodel.runtime.msg.types.service_msgs import ServiceEventInfo
from robomodel.runtime.msg.types.std_srvs import SetBool, Trigger
from tests.conftest import EXAMPLES, ROBOMODEL, ROOT, end_process, past_the_bus_line, unique_domain
from tests.ros2wire.msgtext import write_definitions
from tests.timing import scale, scaled

AGENT = Path(__file__).with_name("sdk_agent.py")
PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"
ARM = EXAMPLES / "two_link_arm/urdf/two_link_arm.urdf.xacro"
ARM_CONTROLLERS = EXAMPLES / "two_link_arm/config/position_controllers.yaml"

TYPES: list[type[Message] | type[Service]] = [
    JointState,
    TFMessage,
    Float64MultiArray,
    String,
    rcl_interfaces.ParameterEvent,
    rcl_interfaces.GetParameters,
    rcl_interfaces.SetParameters,
    rcl_interfaces.ListParameters,
    rcl_interfaces.DescribeParameters,
    controller_manager_msgs.ListControllers,
    controller_manager_msgs.SwitchController,
    controller_manager_msgs.LoadController,
    gazebo_msgs.SpawnEntity,
    gazebo_msgs.ApplyBodyWrench,
    SetBool,
    Trigger,
    ServiceEventInfo,
]


def _sdk_python() -> str:
    path = os.environ.get("ROBOMODEL_ROS2SDK_PYTHON") or str(ROOT / ".venv-ros2sdk/bin/python")
    if not Path(path).exists():
        pytest.fail(
            f"zenoh-ros2-sdk's venv is missing ({path}); `make test` creates it "
            "(python3 -m venv .venv-ros2sdk && .venv-ros2sdk/bin/pip install zenoh-ros2-sdk)"
        )
    return path


@pytest.fixture(scope="module")
def definitions(tmp_path_factory: pytest.TempPathFactory) -> Path:
    # by name only: the text comes from upstream files and rosbags, never robomodel's classes
    return write_definitions(tmp_path_factory.mktemp("msgs"), [t.__typename__ for t in TYPES])


def _sdk(definitions: Path, domain: str, *args: str, timeout: float = 40) -> list[Any]:
    proc = subprocess.run(
        [_sdk_python(), str(AGENT), "--messages", str(definitions), "--domain", domain, *args],
        capture_output=True,
        text=True,
        timeout=scaled(timeout),
        cwd=definitions,
        env={**os.environ, "ROBOMODEL_TEST_TIMEOUT_SCALE": str(scale())},
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    return [
        json.loads(line) for line in proc.stdout.splitlines() if line.startswith(("{", "[", '"'))
    ]


@pytest.fixture
def state_publisher() -> Iterator[str]:
    domain = unique_domain()
    proc = subprocess.Popen(
        [*ROBOMODEL, "publish-state", str(PLANAR), "--delta", "0.01", "--domain-id", domain],
        stderr=subprocess.PIPE,
        text=True,
    )
    assert proc.stderr is not None and "publishing robot" in past_the_bus_line(proc.stderr)
    yield domain
    end_process(proc)


@pytest.fixture
def arm_control() -> Iterator[str]:
    domain = unique_domain()
    proc = subprocess.Popen(
        [*ROBOMODEL, "control", "run", str(ARM), "--controllers", str(ARM_CONTROLLERS),
         "--no-view", "--domain-id", domain],
        stderr=subprocess.PIPE,
        text=True,
    )  # fmt: skip
    assert proc.stderr is not None and "controller manager" in past_the_bus_line(proc.stderr)
    yield domain
    end_process(proc)


def test_type_hashes_agree_with_the_sdk_s(definitions: Path) -> None:
    """zenoh-ros2-sdk computes RIHS01 from the .msg/.srv text with code of its own.

    Left out, with what checks them instead (tests/runtime/test_rmw_zenoh_wire.py): the SDK
    0.1.8 hashes bounded sequences (DescribeParameters' ``FloatingPointRange[<=1]``) wrongly, and
    refuses services whose request is empty (ListControllers, Trigger); robomodel's hashes of
    DescribeParameters, Trigger and std_srvs/Empty equal Jazzy's own.
    """
    skipped = (
        ServiceEventInfo,
        rcl_interfaces.DescribeParameters,
        controller_manager_msgs.ListControllers,
        Trigger,
    )
    checked = [t for t in TYPES if t not in skipped]
    for kind in checked:
        assert _sdk(definitions, "0", "hash", kind.__typename__) == [type_hash(kind)], kind


def test_sdk_receives_joint_states_and_tf(definitions: Path, state_publisher: str) -> None:
    states = _sdk(definitions, state_publisher, "subscribe", "/joint_states", "sensor_msgs/msg/JointState", str(scaled(10)), "3")  # fmt: skip
    assert len(states) == 3 and states[0]["name"] == ["joint_1", "joint_2", "joint_3"]
    # --delta 0.01: every joint moves by 0.01 rad per /joint_states (the publisher's 10 Hz)
    assert states[1]["position"][0] == pytest.approx(states[0]["position"][0] + 0.01, abs=1e-9)
    tf = _sdk(
        definitions,
        state_publisher,
        "subscribe",
        "/tf",
        "tf2_msgs/msg/TFMessage",
        str(scaled(10)),
        "1",
    )
    children = {t["child_frame_id"] for t in tf[0]["transforms"]}
    assert children == {"link_1", "link_2", "gripper"} or {"link_1", "link_2"} <= children
    assert all(t["header"]["frame_id"] for t in tf[0]["transforms"])


def test_sdk_discovery_lists_robomodel_topics_with_ros2_types(
    definitions: Path, state_publisher: str
) -> None:
    wanted = {"/joint_states", "/tf", "/tf_static", "/robot_description"}
    listed: dict[str, list[str]] = {}
    for _ in range(3):  # one timed snapshot each, as for the services below
        [topics] = _sdk(definitions, state_publisher, "topics")
        listed = dict((name, types) for name, types in topics)
        if wanted <= set(listed):
            break
    assert listed["/joint_states"] == ["sensor_msgs/msg/JointState"]
    assert listed["/tf"] == ["tf2_msgs/msg/TFMessage"] == listed["/tf_static"]
    assert listed["/robot_description"] == ["std_msgs/msg/String"]
    offered: dict[str, list[str]] = {}
    for _ in range(3):  # the SDK's discovery is one timed snapshot: a loaded machine may cut it
        [services] = _sdk(definitions, state_publisher, "services")
        offered = dict((name, types) for name, types in services)
        if "/robot_state_publisher/get_parameters" in offered:
            break
    assert offered["/robot_state_publisher/get_parameters"] == ["rcl_interfaces/srv/GetParameters"]


def test_sdk_calls_parameter_and_controller_manager_services(
    definitions: Path, arm_control: str
) -> None:
    hashed = type_hash(controller_manager_msgs.ListControllers)  # the SDK cannot hash it
    [controllers] = _sdk(definitions, arm_control, "call", "/controller_manager/list_controllers", "controller_manager_msgs/srv/ListControllers", "{}", "--type-hash", hashed)  # fmt: skip
    listed = {c["name"]: c for c in controllers["response"]["controller"]}
    assert listed["joint1_position_controller"]["state"] == "active"
    assert (
        listed["joint1_position_controller"]["type"]
        == "position_controllers/JointGroupPositionController"
    )
    assert controllers["type_hash"] == type_hash(controller_manager_msgs.ListControllers)
    [params] = _sdk(definitions, arm_control, "call", "/controller_manager/get_parameters", "rcl_interfaces/srv/GetParameters", '{"names": ["update_rate"]}')  # fmt: skip
    value = params["response"]["values"][0]
    assert value["type"] == 2 and value["integer_value"] == 100  # PARAMETER_INTEGER


def test_sdk_publisher_moves_a_controller_joint(definitions: Path, arm_control: str) -> None:
    command = json.dumps({"data": [0.7]})
    _sdk(definitions, arm_control, "publish", "/joint1_position_controller/commands", "std_msgs/msg/Float64MultiArray", command, "10", "2")  # fmt: skip
    states = _sdk(definitions, arm_control, "subscribe", "/joint_states", "sensor_msgs/msg/JointState", str(scaled(10)), "1")  # fmt: skip
    position = dict(zip(states[0]["name"], states[0]["position"], strict=True))
    assert position["joint1"] == pytest.approx(0.7, abs=1e-6)


def test_robomodel_sees_the_sdk_publisher(definitions: Path) -> None:
    domain = unique_domain()
    talker = subprocess.Popen(
        [_sdk_python(), str(AGENT), "--messages", str(definitions), "--domain", domain,
         "publish", "/chatter", "std_msgs/msg/String", '{"data": "hello from the SDK"}', "10", "20"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=definitions,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + scaled(20)
        listed = ""
        while time.monotonic() < deadline and "/chatter" not in listed:
            run = subprocess.run([*ROBOMODEL, "topic", "list", "-t", "--domain-id", domain],
                                 capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
            listed = run.stdout
        assert "/chatter [std_msgs/msg/String]" in listed
        echo = subprocess.run([*ROBOMODEL, "topic", "echo", "/chatter", "--once", "--domain-id", domain],
                              capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert echo.returncode == 0, echo.stderr
        assert echo.stdout.startswith("data: hello from the SDK")
        info = subprocess.run([*ROBOMODEL, "topic", "info", "/chatter", "-v", "--domain-id", domain],
                              capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert "sdk_talker" in info.stdout
        nodes = subprocess.run([*ROBOMODEL, "node", "list", "--domain-id", domain],
                               capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert "/sdk_talker" in nodes.stdout.split()
        about = subprocess.run([*ROBOMODEL, "node", "info", "/sdk_talker", "--domain-id", domain],
                               capture_output=True, text=True, timeout=scaled(20))  # fmt: skip
        assert "  Publishers:\n    /chatter: std_msgs/msg/String" in about.stdout
    finally:
        talker.kill()
        talker.wait()
