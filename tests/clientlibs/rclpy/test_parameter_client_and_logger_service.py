"""A remote node's parameters through ``rclpy.parameter_client.AsyncParameterClient``, and
a node's logger levels through its logger service (``enable_logger_service=True``), as
demo_nodes_py's async_param_client and use_logger_service use them, on the in-process bus."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.impl.logging_severity import LoggingSeverity
from rclpy.impl.rcutils_logger import RcutilsLogger
from rclpy.node import Node
from rclpy.parameter import Parameter, parameter_dict_from_yaml_file, parameter_value_to_python
from rclpy.parameter_client import AsyncParameterClient

from tests.timing import scaled


@pytest.fixture
def pair(rclpy_inproc: None) -> Any:
    """A blackboard node taking any parameter, a client node, an executor spinning both."""
    board = Node("blackboard", allow_undeclared_parameters=True)
    board.declare_parameter("fixed", 1.5)
    client_node = rclpy.create_node("asker")
    executor = SingleThreadedExecutor()
    executor.add_node(board)
    executor.add_node(client_node)
    yield board, client_node, executor
    executor.shutdown()


def _result(executor: SingleThreadedExecutor, future: Any) -> Any:
    executor.spin_until_future_complete(future, timeout_sec=scaled(10))
    assert future.done()
    return future.result()


def test_a_remote_node_s_parameters_are_set_listed_got_and_deleted(pair: Any) -> None:
    board, client_node, executor = pair
    client = AsyncParameterClient(client_node, "blackboard")
    assert client.wait_for_services(scaled(10))
    set_result = _result(executor, client.set_parameters([
        Parameter("count", Parameter.Type.INTEGER, 10),
        Parameter("label", value="Fee Fi Fo Fum").to_parameter_msg(),  # a message does too
    ]))  # fmt: skip
    assert [r.successful for r in set_result.results] == [True, True]
    assert board.get_parameter("count").value == 10

    listed = _result(executor, client.list_parameters(["count", "label"], 10))
    assert sorted(listed.result.names) == ["count", "label"]
    got = _result(executor, client.get_parameters(["label", "fixed"]))
    assert [parameter_value_to_python(v) for v in got.values] == ["Fee Fi Fo Fum", 1.5]
    types = _result(executor, client.get_parameter_types(["count", "nope"]))
    assert list(types.types) == [Parameter.Type.INTEGER, Parameter.Type.NOT_SET]

    deleted = _result(executor, client.delete_parameters(["label"]))
    assert deleted.results[0].successful
    assert not board.has_parameter("label")
    listed = _result(executor, client.list_parameters())
    assert "label" not in listed.result.names and "count" in listed.result.names


def test_a_parameter_file_is_loaded_into_the_remote_node(pair: Any, tmp_path: Path) -> None:
    board, client_node, executor = pair
    path = tmp_path / "params.yaml"
    path.write_text(
        "/some_node:\n  ros__parameters:\n    gain: 2\n    limits:\n      upper: 0.5\n"
        "/**:\n  ros__parameters:\n    everyone: true\n"
    )
    parameters = parameter_dict_from_yaml_file(str(path))
    assert sorted(parameters) == ["gain", "limits.upper"]  # no wildcard unless asked
    assert parameter_value_to_python(parameters["limits.upper"].value) == 0.5
    assert "everyone" in parameter_dict_from_yaml_file(str(path), use_wildcard=True)
    with pytest.raises(RuntimeError, match="does not contain parameters for /other"):
        parameter_dict_from_yaml_file(str(path), target_nodes=["/other"])

    client = AsyncParameterClient(client_node, "/blackboard")
    loaded = _result(executor, client.load_parameter_file(str(path)))
    assert [r.successful for r in loaded.results] == [True, True]
    assert board.get_parameter("limits.upper").value == 0.5


def test_deleting_a_parameter_of_a_node_with_declared_ones_only_is_refused(
    rclpy_inproc: None,
) -> None:
    strict = Node("strict")
    strict.declare_parameter("gain", 2)
    result = strict.robomodel_node.set_parameters({"gain": None})
    assert not result.successful and "does not allow undeclared" in result.reason
    assert strict.get_parameter("gain").value == 2


class Chatty(Node):
    """Serves its logger levels (``enable_logger_service=True``)."""

    def __init__(self) -> None:
        super().__init__("chatty", enable_logger_service=True)


def test_the_logger_service_reads_and_sets_the_node_s_level(rclpy_inproc: None) -> None:
    from rcl_interfaces.msg import LoggerLevel
    from rcl_interfaces.srv import GetLoggerLevels, SetLoggerLevels

    chatty = Chatty()
    asker = rclpy.create_node("asker")
    executor = SingleThreadedExecutor()
    executor.add_node(chatty)
    executor.add_node(asker)
    get_client = asker.create_client(GetLoggerLevels, "chatty/get_logger_levels")
    set_client = asker.create_client(SetLoggerLevels, "chatty/set_logger_levels")
    assert get_client.wait_for_service(scaled(10)) and set_client.wait_for_service(scaled(10))

    got = _result(executor, get_client.call_async(GetLoggerLevels.Request(names=["chatty"])))
    assert [(level.name, level.level) for level in got.levels] == [("chatty", 0)]  # unset
    assert not chatty.get_logger().is_enabled_for(LoggingSeverity.DEBUG)

    request = SetLoggerLevels.Request()
    request.levels.append(LoggerLevel(name="chatty", level=int(LoggingSeverity.DEBUG)))
    request.levels.append(LoggerLevel(name="chatty.child", level=15))  # no such severity
    done = _result(executor, set_client.call_async(request))
    assert [r.successful for r in done.results] == [True, False]
    assert done.results[1].reason == "Failed reason: Invalid logger level."
    assert chatty.get_logger().is_enabled_for(LoggingSeverity.DEBUG)
    got = _result(executor, get_client.call_async(GetLoggerLevels.Request(names=["chatty"])))
    assert got.levels[0].level == LoggingSeverity.DEBUG
    assert isinstance(chatty.get_logger(), RcutilsLogger)
    chatty.get_logger().set_level(LoggingSeverity.UNSET)  # the levels are the process's
