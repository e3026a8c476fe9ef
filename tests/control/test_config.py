"""Controller YAML files of both formats, the ROS 1 type mapping and file:line errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel.control import ConfigError, load_controller_config

ROS2 = """\
controller_manager:
  ros__parameters:
    update_rate: 250
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
    arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController
/**/arm_controller:
  ros__parameters:
    joints: [joint1, joint2]
    command_interfaces: [position]
    state_interfaces: [position, velocity]
    constraints:
      joint1: {goal: 0.01}
/**:
  ros__parameters:
    use_sim_time: false
"""

ROS1 = """\
rrbot:
  joint_state_controller:
    type: joint_state_controller/JointStateController
    publish_rate: 50
  joint1_position_controller:
    type: effort_controllers/JointPositionController
    joint: joint1
    pid: {p: 100.0, i: 0.01, d: 10.0}
  cmd:
    type: velocity_controllers/JointGroupVelocityController
    joints: [joint1]
"""


def test_ros2_format() -> None:
    cfg = load_controller_config("c.yaml", text=ROS2)
    assert cfg.format == "ros2" and cfg.update_rate_hz == 250
    assert [s.name for s in cfg.controllers] == ["joint_state_broadcaster", "arm_controller"]
    arm = cfg.controller("arm_controller")
    assert arm.params["joints"] == ["joint1", "joint2"]
    assert arm.params["constraints.joint1.goal"] == 0.01
    assert arm.params["use_sim_time"] is False


def test_ros1_format_with_namespace_and_type_mapping() -> None:
    cfg = load_controller_config("c.yaml", text=ROS1)
    assert cfg.format == "ros1" and cfg.namespace == "/rrbot"
    jsc = cfg.controller("joint_state_controller")
    assert jsc.type == "joint_state_broadcaster/JointStateBroadcaster"
    assert jsc.original_type == "joint_state_controller/JointStateController"
    assert jsc.params == {
        "publish_rate": 50,  # by elapsed time, as ROS 1's; not rounded like an update_rate
        "topic": "joint_states",  # ROS 1: relative to the namespace
        "publish_dynamic_joint_states": False,
    }
    pid = cfg.controller("joint1_position_controller")
    assert pid.params["pid.p"] == 100.0
    cmd = cfg.controller("cmd")
    assert cmd.type == "velocity_controllers/JointGroupVelocityController"
    assert cmd.params["topic"] == "~/command"  # ROS 1 topic name


@pytest.mark.parametrize(
    ("text", "where", "what"),
    [
        ("a: {type: x/Y}\n", "c.yaml:1:5", "unknown controller type 'x/Y'"),
        ("a:\n  joint: [1, 2\n", "c.yaml:3:1", "YAML syntax error"),
        (
            "a: {type: joint_state_controller/JointStateController}\nb: {joint: j}\n",
            "c.yaml:2:1",
            "no 'type'",
        ),
        (
            "controller_manager:\n  ros__parameters:\n    update_rate: fast\n",
            "c.yaml:3:5",
            "update_rate",
        ),
        (
            "controller_manager:\n  ros__parameters:\n    x: {type: joint_state_broadcaster/JointStateBroadcaster}\ny:\n  ros__parameters: {a: 1}\n",
            "c.yaml:4:1",
            "does not list",
        ),
    ],
)
def test_errors_have_file_line_column(text: str, where: str, what: str) -> None:
    with pytest.raises(ConfigError) as info:
        load_controller_config("c.yaml", text=text)
    assert str(info.value).startswith(where), str(info.value)
    assert what in str(info.value)


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="cannot read"):
        load_controller_config(tmp_path / "none.yaml")


def test_params_file_relative_to_the_config(tmp_path: Path) -> None:
    (tmp_path / "arm.yaml").write_text(
        "/**:\n  ros__parameters: {command_interfaces: [velocity]}\n"
        "arm:\n  ros__parameters:\n    joints: [a, b]\n    command_interfaces: [position]\n"
    )
    main = tmp_path / "controllers.yaml"
    main.write_text(
        "controller_manager:\n  ros__parameters:\n    arm:\n"
        "      type: joint_trajectory_controller/JointTrajectoryController\n"
        "      params_file: arm.yaml\n"
        "    other:\n      type: joint_state_broadcaster/JointStateBroadcaster\n"
        "      params_file: [missing.yaml]\n"
    )
    with pytest.raises(ConfigError, match=r"controllers.yaml:8:7: params_file 'missing.yaml'"):
        load_controller_config(main)
    main.write_text(main.read_text().replace("      params_file: [missing.yaml]\n", ""))
    arm = load_controller_config(main).controller("arm")
    assert arm.params["joints"] == ["a", "b"] and arm.params["command_interfaces"] == ["position"]


def test_manager_parameters_reach_the_manager_node() -> None:
    from robomodel.control import ControlSystem
    from robomodel.runtime import Context
    from robomodel.runtime.clock import ManualClock
    from tests.control.helpers import arm

    text = ROS2.replace("    update_rate: 250\n", "    update_rate: 250\n    use_sim_time: true\n")
    text = text.replace(
        "    arm_controller:\n      type: joint_trajectory_controller/JointTrajectoryController\n",
        "",
    )
    text = text[: text.index("/**/arm_controller")]
    cfg = load_controller_config("c.yaml", text=text)
    assert cfg.manager_params == {"update_rate": 250, "use_sim_time": True}
    with Context("inproc", clock=ManualClock()) as ctx:
        system = ControlSystem.build(arm(), cfg, context=ctx)
        node = system.manager.node
        assert node is not None and node.get_parameter("use_sim_time") is True
        assert node.get_parameter("update_rate") == 250
