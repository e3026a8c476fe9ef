"""Both dialects' spawners wait for their controller manager through one poll loop."""

from __future__ import annotations

import threading
import time
from types import SimpleNamespace
from typing import Any

import pytest

from robomodel.errors import RobomodelError
from robomodel.launch.nodes.controllers import wait_for_manager
from tests.timing import scaled


class _Runtime:
    """Answers ``list_controllers`` from the ``answer_after``-th call on; refuses before."""

    def __init__(self, answer_after: int | None, offered_after: int = 0) -> None:
        self.answer_after = answer_after
        self.offered_after = offered_after  # graph reads before load/switch_controller appear
        self.graphs = 0
        self.calls: list[tuple[str, float]] = []

    def graph(self, timeout_s: float) -> Any:
        self.graphs += 1
        names = ("list_controllers", "load_controller", "switch_controller")
        offered = names if self.graphs > self.offered_after else names[:1]
        return SimpleNamespace(services={f"/ns/controller_manager/{n}": None for n in offered})

    def call_service(self, name: str, srv_type: Any, request: Any, timeout_s: float) -> Any:
        self.calls.append((name, timeout_s))
        if self.answer_after is None or len(self.calls) < self.answer_after:
            raise RobomodelError(f"service '{name}' not found")
        return srv_type.Response()


def _wait(runtime: _Runtime, timeout_s: float, stopping: threading.Event | None = None, **kw: Any):  # type: ignore[no-untyped-def]
    ctx = SimpleNamespace(runtime=runtime)
    node = SimpleNamespace(stopping=stopping or threading.Event())
    return wait_for_manager(ctx, node, "/ns/controller_manager", timeout_s, **kw)  # type: ignore[arg-type]


def test_ready_once_list_controllers_answers() -> None:
    runtime = _Runtime(answer_after=3)
    # call_timeout_s is compared with what the manager was asked: not scaled
    assert _wait(runtime, scaled(5.0), call_timeout_s=2.0) is True
    assert runtime.calls == [("/ns/controller_manager/list_controllers", 2.0)] * 3


def test_ready_only_once_load_and_switch_controller_are_offered_too() -> None:
    """A manager registers its services one by one: on a real roscore a spawner that called
    load_controller as soon as list_controllers answered found no provider yet."""
    runtime = _Runtime(answer_after=1, offered_after=2)
    assert _wait(runtime, scaled(5.0), call_timeout_s=2.0) is True
    assert runtime.graphs == 3 and len(runtime.calls) == 3


def test_times_out_without_a_manager() -> None:
    start = time.monotonic()
    assert _wait(_Runtime(answer_after=None), 0.3) is False  # the deadline under test
    assert 0.3 <= time.monotonic() - start < scaled(3.0)


def test_zero_timeout_waits_until_stopped_when_asked_to() -> None:
    stopping = threading.Event()
    threading.Timer(0.5, stopping.set).start()
    runtime = _Runtime(answer_after=None)
    assert _wait(runtime, 0.0, stopping, zero_waits_forever=True) is None  # stopped, not timed out
    assert len(runtime.calls) >= 2
    assert _wait(_Runtime(answer_after=None), 0.0) is False  # ROS 1: 0 s is no wait


# -- a manager slower than 10 s ------------------------------------------------------------------
class _SlowManager:
    """A controller manager's services whose ``load_controller`` answers only when the test
    releases it, or fails as a transport does once the caller's deadline has passed."""

    def __init__(self, transport: str) -> None:
        self.transport = SimpleNamespace(name=transport)
        self.calls: list[tuple[str, float]] = []
        self.load_seen = threading.Event()
        self.release = threading.Event()

    def graph(self, timeout_s: float) -> Any:
        names = ("list_controllers", "load_controller", "switch_controller")
        return SimpleNamespace(services={f"/controller_manager/{n}": None for n in names})

    def call_service(self, name: str, srv_type: Any, request: Any, timeout_s: float) -> Any:
        service = name.rsplit("/", 1)[1]
        self.calls.append((service, timeout_s))
        response = srv_type.Response()
        if hasattr(response, "ok"):
            response.ok = True
        if service == "load_controller":
            self.load_seen.set()
            if not self.release.wait(timeout_s):
                raise RobomodelError(f"service '{name}' did not answer in {timeout_s:g} s")
        return response


def _spawner_context(runtime: _SlowManager, dialect: str, args: tuple[str, ...]) -> Any:
    from robomodel.launch.model import NodeSpec
    from robomodel.launch.nodes.base import NodeContext, ViewerRequest

    spec = NodeSpec(dialect, "controller_manager", "spawner", "spawner", args=args)
    return NodeContext(spec, runtime, None, ViewerRequest(), lambda _line: None)


@pytest.mark.parametrize(
    ("dialect", "min_call_s"),
    [
        ("ros1", 3600.0),  # rospy's ServiceProxy: no deadline
        ("ros2", 30.0),  # Jazzy: --service-call-timeout 10 s, 3 attempts
    ],
)
def test_spawners_wait_past_10_s_for_a_slow_load_controller(
    dialect: str, min_call_s: float
) -> None:
    from robomodel.launch.model import NodeSpec
    from robomodel.launch.nodes.base import factory_for

    runtime = _SlowManager(dialect)
    ctx = _spawner_context(runtime, dialect, ("arm_controller",))
    factory = factory_for(NodeSpec(dialect, "controller_manager", "spawner", None))
    assert factory is not None
    node = factory(ctx)
    try:
        assert runtime.load_seen.wait(scaled(30)), runtime.calls
        load_timeouts = [t for s, t in runtime.calls if s == "load_controller"]
        assert load_timeouts and min(load_timeouts) >= min_call_s
        runtime.release.set()
        deadline = time.monotonic() + scaled(30)
        while node.exit_code() is None and "switch_controller" not in dict(runtime.calls):
            assert time.monotonic() < deadline, runtime.calls
            time.sleep(0.05)
        assert [s for s, _ in runtime.calls].count("load_controller") == 1  # not sent again
        assert "switch_controller" in dict(runtime.calls)
    finally:
        runtime.release.set()
        node.stop()


def test_a_manager_answering_after_more_than_10_s_gets_its_controllers_spawned() -> None:
    """A real manager on the in-process bus whose load_controller handler is held until the
    spawner's call has waited 10.5 s (the old 10 s deadline failed it): the ROS 1 spawner
    script, as roslaunch runs it, loads and starts the controller."""
    from robomodel.launch.model import NodeSpec
    from robomodel.launch.runner import LaunchRunner, RunOptions
    from robomodel.xacro import process_file
    from tests.conftest import EXAMPLES

    arm = EXAMPLES / "two_link_arm"
    urdf = process_file(str(arm / "urdf" / "two_link_arm.urdf.xacro")).toxml()
    from robomodel.launch.model import ParamSource

    nodes = [
        NodeSpec("ros2", "controller_manager", "ros2_control_node", None,
                 parameters=(ParamSource(file=arm / "config" / "position_controllers.yaml"),
                             ParamSource(values={"robot_description": urdf}))),
    ]  # fmt: skip
    runner = LaunchRunner(nodes, RunOptions(bus="inproc", headless=True))
    runner.open_bus()
    spin = threading.Thread(target=runner.spin, daemon=True)
    try:
        runner.start_nodes()
        manager = runner.started[0].handle.system.manager
        held = threading.Event()
        release = threading.Event()
        load = manager.load_controller

        def slow_load(*args: Any, **kwargs: Any) -> Any:
            held.set()
            release.wait(scaled(60))
            return load(*args, **kwargs)

        manager.load_controller = slow_load
        spin.start()
        runner._start(NodeSpec("ros1", "controller_manager", "spawner", "spawner",
                               args=("joint_state_broadcaster",)))  # fmt: skip
        assert held.wait(scaled(60))
        seen = time.monotonic()
        while time.monotonic() - seen < 10.5:  # the scenario: an answer after more than 10 s
            time.sleep(0.1)
        release.set()
        deadline = time.monotonic() + scaled(60)
        while {c["name"]: c["state"] for c in manager.list_controllers()}.get(
            "joint_state_broadcaster"
        ) != "active":
            assert time.monotonic() < deadline, manager.list_controllers()
            time.sleep(0.1)
        assert runner.started[1].handle.exit_code() is None  # the ROS 1 spawner stays up
    finally:
        runner._stop.set()
        spin.join(scaled(30))
        runner.shutdown()


def test_ros2_spawner_timeouts_default_to_jazzy_s() -> None:
    """spawner.py (jazzy): --controller-manager-timeout 0 (wait for ever), --service-call-timeout
    10, --switch-timeout 5; ROS 1's spawner: --timeout 30."""
    from robomodel.launch.nodes.controllers import parse_spawner_args
    from robomodel.launch.nodes.ros2_control import parse_ros2_spawner_args

    default = parse_ros2_spawner_args(("jsb",))
    assert (default.timeout_s, default.service_call_timeout_s, default.switch_timeout_s) == (
        0.0, 10.0, 5.0,
    )  # fmt: skip
    given = parse_ros2_spawner_args(
        ("jsb", "--service-call-timeout", "25", "--switch-timeout=2", "-n", "r1")
    )
    assert (given.service_call_timeout_s, given.switch_timeout_s, given.namespace) == (
        25.0, 2.0, "r1",
    )  # fmt: skip
    with pytest.raises(RobomodelError, match="--service-call-timeout: invalid float value: 'x'"):
        parse_ros2_spawner_args(("jsb", "--service-call-timeout", "x"))
    assert parse_spawner_args(("jsc",)).timeout_s == 30.0
