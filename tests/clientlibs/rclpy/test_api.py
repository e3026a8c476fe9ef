"""The parts of rclpy's API that need no bus: time and duration arithmetic, QoS profiles and
presets, loggers, ``--ros-args`` handling, parameters, and what robomodel does not offer."""

from __future__ import annotations

import importlib
import time
from pathlib import Path

import pytest
import rclpy
from rclpy.clock import Clock, ClockType
from rclpy.duration import Duration
from rclpy.time import Time

MODULES = [
    "rclpy", "rclpy.action", "rclpy.action.client", "rclpy.action.server", "rclpy.callback_groups",
    "rclpy.client", "rclpy.clock", "rclpy.clock_type", "rclpy.context", "rclpy.duration", "rclpy.exceptions",
    "rclpy.executors", "rclpy.logging", "rclpy.node", "rclpy.parameter", "rclpy.publisher",
    "rclpy.qos", "rclpy.service", "rclpy.signals", "rclpy.subscription", "rclpy.task", "rclpy.time",
    "rclpy.timer", "rclpy.topic_endpoint_info", "rclpy.utilities", "rclpy.wait_for_message",
    "rclpy.event_handler", "rclpy.qos_overriding_options", "rclpy.parameter_client",
    "rclpy.service_introspection", "rclpy.logging_service", "rclpy.impl",
    "rclpy.impl.logging_severity", "rclpy.impl.rcutils_logger", "sensor_msgs_py",
    "sensor_msgs_py.point_cloud2",
]  # fmt: skip


@pytest.mark.parametrize("name", MODULES)
def test_every_public_name_resolves(name: str) -> None:
    module = importlib.import_module(name)
    assert module is importlib.import_module(f"robomodel.clientlibs.{name}")  # one module
    for public in getattr(module, "__all__", ()):
        assert hasattr(module, public), f"{name}.{public}"


def test_time_and_duration_arithmetic() -> None:
    t = Time(seconds=1, nanoseconds=500_000_000, clock_type=ClockType.ROS_TIME)
    d = Duration(seconds=0.25)
    assert (t + d).nanoseconds == 1_750_000_000
    assert (d + t).nanoseconds == 1_750_000_000
    assert (t - d).nanoseconds == 1_250_000_000
    assert t - Time(seconds=1, clock_type=ClockType.ROS_TIME) == Duration(nanoseconds=500_000_000)
    assert t.seconds_nanoseconds() == (1, 500_000_000)
    assert Duration(seconds=1) * 2.5 == Duration(seconds=2.5) and -d < d
    assert Duration(seconds=-1.5).to_msg().sec == -2  # builtin_interfaces: nanosec >= 0
    assert Duration(seconds=-1.5).to_msg().nanosec == 500_000_000
    msg = t.to_msg()
    assert (msg.sec, msg.nanosec) == (1, 500_000_000)
    from builtin_interfaces.msg import Time as TimeMsg

    assert type(msg) is TimeMsg
    assert Time.from_msg(msg) == t
    assert Duration.from_msg(d.to_msg()) == d
    with pytest.raises(TypeError):
        _ = t < Time(seconds=2)  # another clock type
    with pytest.raises(TypeError):
        _ = t + t
    with pytest.raises(ValueError, match="negative"):
        _ = Time(seconds=0) - Duration(seconds=1)


def test_clocks() -> None:
    system = Clock()
    before = time.time_ns()
    now = system.now()
    assert now.clock_type == ClockType.SYSTEM_TIME and abs(now.nanoseconds - before) < 10**9
    steady = Clock(clock_type=ClockType.STEADY_TIME)
    assert steady.now() <= steady.now()


def test_qos_profiles_and_presets() -> None:
    from rclpy.qos import (
        DurabilityPolicy,
        HistoryPolicy,
        QoSDurabilityPolicy,
        QoSPresetProfiles,
        QoSProfile,
        ReliabilityPolicy,
        qos_profile_sensor_data,
        qos_profile_services_default,
    )

    from robomodel.runtime.qos import Durability, History, Reliability

    latched = QoSProfile(depth=1, durability=QoSDurabilityPolicy.TRANSIENT_LOCAL)
    robomodel = latched.to_robomodel()
    assert (robomodel.depth, robomodel.durability) == (1, Durability.TRANSIENT_LOCAL)
    assert robomodel.reliability == Reliability.RELIABLE
    sensor = qos_profile_sensor_data.to_robomodel()
    assert (sensor.depth, sensor.reliability) == (5, Reliability.BEST_EFFORT)
    assert QoSPresetProfiles.get_from_short_key("sensor_data") == qos_profile_sensor_data
    assert qos_profile_services_default.depth == 10
    keep_all = QoSProfile(history=HistoryPolicy.KEEP_ALL).to_robomodel()
    assert keep_all.history == History.KEEP_ALL
    profile = QoSProfile(depth=3)
    profile.reliability = ReliabilityPolicy.BEST_EFFORT
    profile.deadline = Duration(seconds=0.5)
    converted = profile.to_robomodel()
    assert converted.reliability == Reliability.BEST_EFFORT and converted.deadline_ns == 500_000_000
    assert DurabilityPolicy.VOLATILE == 2
    with pytest.raises(TypeError, match="history"):
        QoSProfile()


def test_loggers_print_as_rcutils_with_throttle_once_and_skip_first(
    capfd: pytest.CaptureFixture[str],
) -> None:
    from rclpy.logging import LoggingSeverity, get_logger

    logger = get_logger("lesson")
    logger.debug("hidden")  # INFO by default
    for i in range(5):
        logger.info(f"once {i}", once=True)
        logger.warning(f"skip {i}", skip_first=True)
        logger.error(f"throttled {i}", throttle_duration_sec=60.0)
    logger.set_level(LoggingSeverity.DEBUG)
    logger.get_child("part").debug("now shown")
    lines = capfd.readouterr().err.splitlines()
    assert [line.split("]: ")[1] for line in lines] == [
        "once 0", "throttled 0", "skip 1", "skip 2", "skip 3", "skip 4", "now shown"
    ]  # fmt: skip
    assert lines[0].startswith("[INFO] [") and "] [lesson]: " in lines[0]
    assert lines[2].startswith("[WARN]") and lines[-1].split("] [")[-1] == "lesson.part]: now shown"
    logger.set_level(LoggingSeverity.INFO)


def test_remove_ros_args_and_parse_errors() -> None:
    from rclpy.utilities import remove_ros_args

    from robomodel.clientlibs.rclpy._arguments import RosArgumentsError, parse_ros_arguments

    argv = ["prog", "in", "--ros-args", "-r", "a:=b", "-p", "x:=1", "--params-file", "f.yaml",
            "--log-level", "debug", "--", "out", "--ros-args", "--enable-rosout-logs"]  # fmt: skip
    assert remove_ros_args(argv) == ["prog", "in", "out"]
    parsed = parse_ros_arguments(argv)
    assert parsed.remappings("any") == {"a": "b"}
    assert parsed.params == [(None, "x", 1), Path("f.yaml")]
    assert parsed.log_levels == [(None, "debug")]
    node_specific = parse_ros_arguments(
        ["--ros-args", "-r", "talker:chatter:=c", "-p", "talker:k:=v"]
    )
    assert node_specific.remappings("talker") == {"chatter": "c"}
    assert node_specific.remappings("listener") == {}
    with pytest.raises(RosArgumentsError, match="unknown ROS argument '--bogus'"):
        parse_ros_arguments(["--ros-args", "--bogus"])
    with pytest.raises(RosArgumentsError, match="expected from:=to"):
        parse_ros_arguments(["--ros-args", "-r", "chatter"])


def test_parameter_types() -> None:
    from rclpy.parameter import Parameter

    assert Parameter("a", value=True).type_ == Parameter.Type.BOOL
    assert Parameter("a", value=[1, 2]).type_ == Parameter.Type.INTEGER_ARRAY
    assert Parameter("a", value=[1.0]).type_ == Parameter.Type.DOUBLE_ARRAY
    assert Parameter("a", value=["x"]).type_ == Parameter.Type.STRING_ARRAY
    assert Parameter("a").type_ == Parameter.Type.NOT_SET
    with pytest.raises(ValueError, match="do not agree"):
        Parameter("a", Parameter.Type.INTEGER, "x")
    message = Parameter("gain", value=2.5).to_parameter_msg()
    assert message.value.type == 3 and message.value.double_value == 2.5
    assert Parameter.from_parameter_msg(message) == Parameter("gain", value=2.5)


def test_what_is_not_offered_raises_naming_it(rclpy_inproc: None) -> None:
    node = rclpy.create_node("limits")
    from std_msgs.msg import String

    calls = {
        "Node.undeclare_parameter()": lambda: node.undeclare_parameter("use_sim_time"),
        "create_subscription(raw=True) on the in-process bus": lambda: node.create_subscription(
            String, "t", lambda m: None, 10, raw=True
        ),
        "a subscription callback taking (msg, message_info)": lambda: node.create_subscription(
            String, "t", lambda m, info: None, 10
        ),
        "Node(start_parameter_services=False)": lambda: rclpy.create_node(
            "x", start_parameter_services=False
        ),
    }
    for name, call in calls.items():
        with pytest.raises(
            NotImplementedError,
            match=rf"^{name.replace('(', '.').replace(')', '.')} is not offered",
        ):
            call()


def test_the_node_s_clock_and_log_lines_on_rosout(rclpy_inproc: None) -> None:
    from rcl_interfaces.msg import Log

    node = rclpy.create_node("clocked", namespace="/ns")
    now = node.get_clock().now()
    assert now.clock_type == ClockType.ROS_TIME and abs(now.nanoseconds - time.time_ns()) < 10**9
    assert not node.get_clock().ros_time_is_active
    heard: list[object] = []
    listener = rclpy.create_node("listener")
    listener.create_subscription(Log, "/rosout", heard.append, 100)
    node.get_logger().warning("careful")
    deadline = time.monotonic() + 5
    while (
        not any(getattr(m, "msg", "") == "careful" for m in heard) and time.monotonic() < deadline
    ):
        rclpy.spin_once(listener, timeout_sec=0.05)
    [line] = [m for m in heard if getattr(m, "msg", "") == "careful"]
    assert line.name == "/ns/clocked" and line.level == 30  # type: ignore[attr-defined]
    from rclpy.parameter import Parameter

    node.set_parameters([Parameter("use_sim_time", value=True)])
    assert node.get_clock().ros_time_is_active and node.get_clock().now().nanoseconds == 0


def test_wait_for_message_and_a_logger_outliving_its_node(rclpy_inproc: None) -> None:
    from rclpy.wait_for_message import wait_for_message
    from std_msgs.msg import String

    node = rclpy.create_node("waiter")
    assert wait_for_message(String, node, "/quiet", time_to_wait=0.05) == (False, None)
    publisher = node.create_publisher(String, "/said", 10)
    node.create_timer(0.01, lambda: publisher.publish(String(data="here")))
    ok, msg = wait_for_message(String, node, "/said", time_to_wait=5.0)
    assert ok and msg.data == "here"
    logger = node.get_logger()
    node.destroy_node()
    assert logger.info("after the node")  # printed; no /rosout to publish on any more
