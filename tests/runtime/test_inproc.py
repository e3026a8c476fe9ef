"""The in-process bus: deterministic delivery, timers, latching, sim time, robustness."""

from __future__ import annotations

import logging

import pytest

from robomodel.runtime import Context, ManualClock, latched
from robomodel.runtime.msg import Clock, Float64, String, Time
from robomodel.runtime.param_client import ParameterClient
from robomodel.runtime.params import ParameterError, SetResult


def _run(seed_order: list[str]) -> list[tuple[float, str, float]]:
    ctx = Context(clock=ManualClock())
    log: list[tuple[float, str, float]] = []
    talker = ctx.create_node("talker")
    pub = talker.create_publisher(Float64, "chatter")
    for name in seed_order:
        node = ctx.create_node(name)
        node.create_subscription(
            Float64, "/chatter", lambda m, n=name: log.append((ctx.clock.now_s(), n, m.data))
        )
    talker.create_timer(0.1, lambda: pub.publish(Float64(round(ctx.clock.now_s(), 9))))
    ctx.advance(1.0)
    return log


def test_deterministic_and_exact_timer_times() -> None:
    first, second = _run(["a", "b"]), _run(["a", "b"])
    assert first == second
    assert [t for t, n, _ in first if n == "a"] == [
        pytest.approx(0.1 * k, abs=1e-12) for k in range(1, 11)
    ]
    assert first[-1][0] == 1.0  # the 10th tick lands exactly on 1.0 (no accumulated drift)


def test_transient_local_reaches_late_subscribers() -> None:
    ctx = Context(clock=ManualClock())
    node = ctx.create_node("rsp")
    pub = node.create_publisher(String, "robot_description", latched())
    pub.publish(String("first"))
    pub.publish(String("second"))
    late: list[str] = []
    volatile: list[str] = []
    other = ctx.create_node("viewer")
    other.create_subscription(
        String, "/robot_description", lambda m: late.append(m.data), latched()
    )
    other.create_subscription(String, "/robot_description", lambda m: volatile.append(m.data))
    ctx.spin_once()
    assert late == ["second"] and volatile == []


def test_type_clash_warned_and_not_delivered(caplog: pytest.LogCaptureFixture) -> None:
    ctx = Context(clock=ManualClock())
    node = ctx.create_node("n")
    got: list[object] = []
    node.create_subscription(String, "/x", got.append)
    pub = node.create_publisher(Float64, "/x")
    with caplog.at_level(logging.WARNING):
        pub.publish(Float64(1.0))
        pub.publish(Float64(2.0))
        ctx.spin_once()
    assert got == []
    assert (
        sum(
            "published as std_msgs/msg/Float64 but subscribed as" in r.message
            for r in caplog.records
        )
        == 1
    )


def test_failing_callback_does_not_kill_the_node(caplog: pytest.LogCaptureFixture) -> None:
    ctx = Context(clock=ManualClock())
    node = ctx.create_node("n")
    got: list[float] = []

    def bad(msg: Float64) -> None:
        if msg.data < 0:
            raise ValueError("negative")
        got.append(msg.data)

    node.create_subscription(Float64, "/x", bad)
    pub = node.create_publisher(Float64, "/x")
    with caplog.at_level(logging.ERROR):
        for value in (1.0, -1.0, 2.0):
            pub.publish(Float64(value))
        ctx.spin_once()
    assert got == [1.0, 2.0]
    assert any("callback failed" in r.message for r in caplog.records)


def test_use_sim_time_follows_clock_topic() -> None:
    ctx = Context(clock=ManualClock(100.0))
    sim = ctx.create_node("sim")
    clock_pub = sim.create_publisher(Clock, "/clock")
    node = ctx.create_node("ctrl", parameters={"use_sim_time": True})
    ticks: list[float] = []
    node.create_timer(0.5, lambda: ticks.append(node.get_clock().now_s()))
    assert node.get_clock().now_s() == 0.0
    for k in range(1, 6):
        clock_pub.publish(Clock(Time.from_seconds(0.4 * k)))
        ctx.spin_once()
    assert node.now() == Time.from_seconds(2.0)
    assert ticks == [0.8, 1.2, 1.6, 2.0]  # fires whenever sim time has passed a period
    assert ctx.create_node("wall").get_clock().now_s() == 100.0
    assert node.set_parameters({"use_sim_time": False}).successful
    assert node.get_clock().now_s() == 100.0


def test_graph_and_parameter_service() -> None:
    ctx = Context(clock=ManualClock())
    node = ctx.create_node("jsp", "/arm")
    node.declare_parameter("rate", 10)
    node.create_publisher(Float64, "joint_states")
    graph = ctx.graph()
    assert "/arm/jsp" in graph.nodes
    assert graph.topics["/arm/joint_states"].types == {"std_msgs/msg/Float64"}
    # rclcpp's ParameterService (six rcl_interfaces services) and rcl's get_type_description
    assert {s for s in graph.services if s.startswith("/arm/jsp/")} == {
        f"/arm/jsp/{name}"
        for name in (
            "get_type_description",
            "describe_parameters",
            "get_parameter_types",
            "get_parameters",
            "list_parameters",
            "set_parameters",
            "set_parameters_atomically",
        )
    }
    params = ParameterClient(ctx, "/arm/jsp")
    assert params.list_names() == ["rate", "use_sim_time"]
    assert params.get(["rate"]) == {"rate": 10}
    assert params.set({"rate": 20}) == [SetResult(True, "")]
    assert node.get_parameter("rate") == 20
    refused = params.set({"rate": "fast", "use_sim_time": False})
    assert not refused[0].successful and refused[1].successful  # each on its own
    atomic = params.set_atomically({"rate": 30, "nope": 1})
    assert not atomic.successful and node.get_parameter("rate") == 20  # all or nothing
    with pytest.raises(ParameterError, match="not set"):
        params.get(["rate", "nope"])  # rclcpp answers nothing when one name is unknown
    described = params.describe(["rate"])
    assert described[0].name == "rate" and described[0].type == 2  # PARAMETER_INTEGER


def test_parameter_events_are_published() -> None:
    from robomodel.runtime.msg.types.rcl_interfaces import ParameterEvent

    ctx = Context(clock=ManualClock())
    events: list[ParameterEvent] = []
    ctx.create_node("watcher").create_subscription(
        ParameterEvent, "/parameter_events", events.append, 1000
    )
    node = ctx.create_node("talker")
    node.declare_parameter("gain", 1.5)
    node.set_parameters({"gain": 2.0})
    ctx.spin_once()
    mine = [e for e in events if e.node == "/talker"]
    assert [p.name for e in mine for p in e.new_parameters] == ["use_sim_time", "gain"]
    changed = [p for e in mine for p in e.changed_parameters]
    assert [(p.name, p.value.double_value) for p in changed] == [("gain", 2.0)]
