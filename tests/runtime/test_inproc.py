"""The in-process bus: deterministic delivery, timers, latching, sim time, robustness."""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

import pytest

from robomodel.errors import RobomodelError
from robomodel.runtime import Context, ManualClock, latched
from robomodel.runtime.msg import Clock, Float64, String, Time
from robomodel.runtime.param_client import ParameterClient
from robomodel.runtime.params import ParameterError, SetResult
from tests.timing import scaled


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


def _sim_clock_publisher(ctx: Context) -> Callable[[float], None]:
    """A function that publishes /clock at ``t_s`` and spins once."""
    clock_pub = ctx.create_node("sim").create_publisher(Clock, "/clock")

    def at(t_s: float) -> None:
        clock_pub.publish(Clock(Time.from_seconds(t_s)))
        ctx.spin_once()

    return at


def test_a_sim_time_timer_goes_on_after_the_clock_went_back() -> None:
    """A simulation reset sends /clock back: the timer's next tick is a period after the jump,
    as rcl's timers do, not once the clock is back where it was."""
    ctx = Context(clock=ManualClock(100.0))
    at = _sim_clock_publisher(ctx)
    node = ctx.create_node("ctrl", parameters={"use_sim_time": True})
    ticks: list[float] = []
    node.create_timer(0.5, lambda: ticks.append(node.get_clock().now_s()))
    for t_s in (4.0, 10.0, 0.2, 0.6, 0.75, 1.25):  # back to 0.2 s: a reset
        at(t_s)
    assert ticks == [4.0, 10.0, 0.75, 1.25]


def test_the_tf_listener_forgets_dynamic_transforms_when_time_goes_back(
    caplog: pytest.LogCaptureFixture,
) -> None:
    """As tf2_ros's listener: a /tf after the clock went back clears the buffer's dynamic
    transforms (their stamps are of a time that is no more), with tf2_ros's warning; static
    transforms stay."""
    from robomodel.runtime.msg import TFMessage, TransformStamped
    from robomodel.runtime.qos import Durability, QoSProfile
    from robomodel.runtime.tf_listener import TransformListener

    ctx = Context(clock=ManualClock(100.0))
    at = _sim_clock_publisher(ctx)
    listener = TransformListener(ctx.create_node("viewer", parameters={"use_sim_time": True}))
    talker = ctx.create_node("talker")
    tf_pub = talker.create_publisher(TFMessage, "/tf", 10)
    static_qos = QoSProfile(10, Durability.TRANSIENT_LOCAL)
    static_pub = talker.create_publisher(TFMessage, "/tf_static", static_qos)

    def transform(parent: str, child: str, t_s: float) -> TFMessage:
        tf = TransformStamped()
        tf.header.frame_id, tf.child_frame_id = parent, child
        tf.header.stamp = Time.from_seconds(t_s)
        tf.transform.rotation.w = 1.0
        return TFMessage(transforms=[tf])

    static_pub.publish(transform("base", "laser", 0.0))
    at(10.0)
    tf_pub.publish(transform("map", "odom", 10.0))
    ctx.spin_once()
    assert listener.buffer.can_transform("map", "odom")
    at(1.0)  # a simulation reset
    with caplog.at_level(logging.WARNING):
        tf_pub.publish(transform("map", "base", 1.0))
        ctx.spin_once()
    assert not listener.buffer.can_transform("map", "odom")
    assert listener.buffer.can_transform("map", "laser")  # the new /tf and the static one
    assert [r.getMessage() for r in caplog.records] == [
        "Detected jump back in time of 9s. Clearing TF buffer."
    ]


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


def test_transient_local_keeps_the_last_depth_messages() -> None:
    """A late subscriber gets the publisher's last ``depth`` messages, oldest first, as DDS
    and rmw_zenoh's transient-local publication cache (``history`` of ``depth``) keep them."""
    ctx = Context(clock=ManualClock())
    pub = ctx.create_node("talker").create_publisher(String, "log", latched(depth=3))
    for k in range(5):
        pub.publish(String(f"m{k}"))
    late: list[str] = []
    ctx.create_node("late").create_subscription(
        String, "/log", lambda m: late.append(m.data), latched(depth=3)
    )
    ctx.spin_once()
    assert late == ["m2", "m3", "m4"]


def test_destroyed_endpoints_leave_the_graph_and_deliver_nothing() -> None:
    ctx = Context(clock=ManualClock())
    pub = ctx.create_node("talker").create_publisher(String, "chatter", latched(depth=2))
    heard: list[str] = []
    ear = ctx.create_node("ear")
    sub = ear.create_subscription(String, "/chatter", lambda m: heard.append(m.data))
    kept = ear.create_subscription(String, "/chatter", lambda m: heard.append("kept " + m.data))
    sub.destroy()
    sub.destroy()  # twice: nothing more happens
    pub.publish(String("a"))
    ctx.spin_once()
    assert heard == ["kept a"]
    topic = ctx.graph().topics["/chatter"]
    assert [e.node for e in topic.subscribers] == ["/ear"]
    pub.destroy()
    pub.destroy()
    assert ctx.graph().topics["/chatter"].publishers == []
    late: list[str] = []
    ear.create_subscription(String, "/chatter", lambda m: late.append(m.data), latched(depth=2))
    ctx.spin_once()
    assert late == []  # a destroyed publisher's history goes with it
    kept.destroy()
    ctx.shutdown()
    # the context is closed: handles destroyed now find no lists, and that is no error
    pub.destroy()
    kept.destroy()


def test_a_destroyed_service_handle_does_not_remove_its_successor() -> None:
    from robomodel.runtime.msg.types.std_srvs import Trigger, Trigger_Response

    ctx = Context(clock=ManualClock())
    node = ctx.create_node("server")
    first = node.create_service(Trigger, "reset", lambda r: Trigger_Response(True, "first"))
    first.destroy()
    second = node.create_service(Trigger, "reset", lambda r: Trigger_Response(True, "second"))
    first.destroy()  # the old handle again: the new service stays
    assert ctx.call_service("/reset", Trigger).message == "second"
    assert set(ctx.graph().services) >= {"/reset"}
    second.destroy()
    assert "/reset" not in ctx.graph().services


def test_the_graph_lists_each_endpoint_with_its_node_type_and_qos() -> None:
    from robomodel.runtime.msg.types.std_srvs import Trigger, Trigger_Response
    from robomodel.runtime.qos import QoSProfile

    ctx = Context(clock=ManualClock())
    ctx.create_node("talker").create_publisher(String, "chatter", latched(depth=4))
    ctx.create_node("ear").create_subscription(String, "/chatter", lambda m: None, 7)
    ctx.create_node("server").create_service(Trigger, "reset", lambda r: Trigger_Response())
    graph = ctx.graph()
    assert {"/talker", "/ear", "/server"} <= graph.nodes
    topic = graph.topics["/chatter"]
    assert topic.types == {"std_msgs/msg/String"}
    assert [(e.node, e.topic, e.type_name, e.qos) for e in topic.publishers] == [
        ("/talker", "/chatter", "std_msgs/msg/String", latched(depth=4))
    ]
    assert [(e.node, e.topic, e.type_name, e.qos) for e in topic.subscribers] == [
        ("/ear", "/chatter", "std_msgs/msg/String", QoSProfile(7))
    ]
    server = graph.services["/reset"]
    assert [(e.node, e.type_name) for e in server.servers] == [("/server", "std_srvs/srv/Trigger")]


def test_nodes_of_one_name_are_counted_and_warned_about(caplog: pytest.LogCaptureFixture) -> None:
    ctx = Context(clock=ManualClock())
    first = ctx.create_node("twin")
    with caplog.at_level(logging.WARNING, logger="robomodel.runtime"):
        second = ctx.create_node("twin")
    assert "a node named /twin already exists; names should be unique" in [
        r.getMessage() for r in caplog.records
    ]
    assert "/twin" in ctx.graph().nodes
    first.destroy()
    assert "/twin" in ctx.graph().nodes  # the other one still runs
    second.destroy()
    assert "/twin" not in ctx.graph().nodes
    third = ctx.create_node("twin")
    assert "/twin" in ctx.graph().nodes
    third.destroy()
    assert "/twin" not in ctx.graph().nodes


def test_publishing_the_wrong_type_names_both_types() -> None:
    ctx = Context(clock=ManualClock())
    pub = ctx.create_node("talker").create_publisher(String, "chatter")
    with pytest.raises(RobomodelError) as caught:
        pub.publish(Float64(1.0))  # type: ignore[arg-type]
    assert str(caught.value) == (
        "publisher on /chatter has type std_msgs/msg/String, got std_msgs/msg/Float64"
    )


def test_each_type_clash_is_warned_once_with_its_topic(caplog: pytest.LogCaptureFixture) -> None:
    """Once per (topic, published type, subscribed type), at the first message for a
    subscription made first, and at once for a late transient-local subscription."""
    ctx = Context(clock=ManualClock())
    got: list[object] = []
    ear = ctx.create_node("ear")
    ear.create_subscription(String, "/a", got.append)
    talker = ctx.create_node("talker")
    to_a = talker.create_publisher(Float64, "a", latched())
    to_b = talker.create_publisher(Float64, "b", latched())
    ear.create_subscription(String, "/c", got.append, latched())  # no publisher yet: nothing
    to_c = talker.create_publisher(Float64, "c")
    with caplog.at_level(logging.WARNING, logger="robomodel.runtime"):
        assert to_c.get_subscription_count() == 0  # asked before any message: warned here
        for _ in range(2):
            to_a.publish(Float64(1.0))
            to_b.publish(Float64(2.0))
        ear.create_subscription(String, "/b", got.append, latched())  # history of another type
        ctx.spin_once()
    assert got == []
    assert [r.getMessage() for r in caplog.records] == [
        f"topic /{t} is published as std_msgs/msg/Float64 but subscribed as std_msgs/msg/String "
        "by /ear; messages are not delivered"
        for t in ("c", "a", "b")
    ]


def test_a_node_name_in_use_is_warned_about_until_its_last_node_goes(
    caplog: pytest.LogCaptureFixture,
) -> None:
    ctx = Context(clock=ManualClock())
    warning = "a node named /twin already exists; names should be unique"

    def warned() -> bool:
        found = warning in [r.getMessage() for r in caplog.records]
        caplog.clear()
        return found

    with caplog.at_level(logging.WARNING, logger="robomodel.runtime"):
        first = ctx.create_node("twin")
        assert not warned()
        second = ctx.create_node("twin")
        assert warned()
        first.destroy()
        third = ctx.create_node("twin")  # the second still runs
        assert warned()
        second.destroy()
        third.destroy()
        fourth = ctx.create_node("twin")
        assert not warned()
    ctx.shutdown()
    fourth.destroy()  # after the context: no error


def test_services_answer_from_the_spinning_thread_and_say_why_not() -> None:
    """A call from another thread runs the handler on the spinning thread (as a call from
    another process would) and waits; the errors name the service."""
    import threading

    from robomodel.runtime.msg.types.std_srvs import Trigger, Trigger_Response
    from robomodel.runtime.transport.base import Deferred, ServiceCallError

    ctx = Context()
    node = ctx.create_node("server")
    threads: list[int] = []
    later: list[Deferred] = []

    def now(_: object) -> Trigger_Response:
        threads.append(threading.get_ident())
        return Trigger_Response(True, "now")

    def deferred(_: object) -> Deferred:
        answer = Deferred()
        later.append(answer)
        ctx.executor.post(lambda: answer.resolve(Trigger_Response(True, "later")))
        return answer

    def failing(_: object) -> Trigger_Response:
        raise ValueError("boom")

    node.create_service(Trigger, "now", now)
    node.create_service(Trigger, "later", deferred)
    node.create_service(Trigger, "fails", failing)
    node.create_service(Trigger, "never", lambda _: Deferred())
    with pytest.raises(ServiceCallError) as caught:
        ctx.call_service("/nope", Trigger)
    assert str(caught.value) == "service '/nope' not found; services: " + ", ".join(
        sorted(ctx.graph().services)
    )
    with pytest.raises(ServiceCallError, match=r"^service '/never' answers later; call it from another thread than the spinner$"):  # fmt: skip
        ctx.call_service("/never", Trigger)
    stop = threading.Event()
    spinner = threading.Thread(target=lambda: ctx.spin(until=stop.is_set), daemon=True)
    spinner.start()
    try:
        assert ctx.call_service("/now", Trigger, timeout_s=scaled(5)).message == "now"
        assert threads == [spinner.ident]
        assert ctx.call_service("/later", Trigger, timeout_s=scaled(5)).message == "later"
        with pytest.raises(ServiceCallError) as caught:
            ctx.call_service("/fails", Trigger, timeout_s=scaled(5))
        assert str(caught.value) == "service '/fails' failed: boom"
        with pytest.raises(ServiceCallError) as caught:
            ctx.call_service("/never", Trigger, timeout_s=0.25)
        assert str(caught.value) == "service '/never' did not answer in 0.25 s"
    finally:
        stop.set()
        spinner.join(scaled(5))
    ctx.shutdown()
    empty = Context()
    with pytest.raises(ServiceCallError, match=r"^service '/nope' not found; services: \(none\)$"):
        empty.transport.call_service("/nope", Trigger, Trigger.Request())
    empty.shutdown()


def test_a_failing_handler_is_one_warning_and_the_caller_learns_why(
    caplog: pytest.LogCaptureFixture,
) -> None:
    import threading

    from robomodel.runtime.msg.types.std_srvs import SetBool, SetBool_Response
    from robomodel.runtime.transport.base import ServiceCallError

    def check(request: object) -> SetBool_Response:
        if not request.data:  # type: ignore[attr-defined]
            raise ValueError("data must be true")
        return SetBool_Response(True, "checked")

    ctx = Context()
    ctx.create_node("server").create_service(SetBool, "check", check)
    with (
        caplog.at_level(logging.WARNING, logger="robomodel.runtime"),
        pytest.raises(ServiceCallError) as caught,
    ):
        ctx.call_service("/check", SetBool, SetBool.Request(False))
    assert str(caught.value) == "service '/check' failed: data must be true"
    assert [r.getMessage() for r in caplog.records] == [
        "service /check failed: ValueError: data must be true"
    ]
    stop = threading.Event()
    spinner = threading.Thread(target=lambda: ctx.spin(until=stop.is_set), daemon=True)
    spinner.start()
    try:  # from another thread, the request reaches the handler as well
        reply = ctx.call_service("/check", SetBool, SetBool.Request(True), timeout_s=scaled(5))
        assert reply == SetBool_Response(True, "checked")
    finally:
        stop.set()
        spinner.join(scaled(5))
    ctx.shutdown()


def test_a_message_of_another_class_of_its_type_arrives_as_the_subscriber_s_class() -> None:
    """A publisher's message of another class of the same type (a client library's face, as
    rospy's genpy-shaped JointState) reaches a subscriber as an instance of the subscriber's
    own class, with the same fields; one of the subscriber's own class arrives as it is."""
    from robomodel.clientlibs.messages import message_class
    from robomodel.runtime.msg import JointState

    face = message_class("sensor_msgs/msg/JointState", "genpy")
    ctx = Context()
    node = ctx.create_node("faces")
    got: list[Any] = []
    node.create_subscription(JointState, "/faces", got.append, 10)
    by_face = node.create_publisher(face, "/faces", 10)
    by_own = node.create_publisher(JointState, "/faces", 10)
    sent = face()
    sent.name, sent.position = ["a"], [1.5]
    by_face.publish(sent)
    own = JointState(name=["b"], position=[2.5])
    by_own.publish(own)
    ctx.spin_once(0.1)
    ctx.spin_once(0.1)
    assert [type(m) for m in got] == [JointState, JointState]
    assert (list(got[0].name), list(got[0].position)) == (["a"], [1.5])
    assert got[1] is own
    ctx.shutdown()


def test_the_graph_reads_from_another_thread_while_endpoints_come_and_go() -> None:
    """A bridge's poller reads the graph on a thread of its own while the executor's thread
    makes and destroys nodes, publishers, subscriptions and services: no read fails (iterating
    a table as it changed size did, at once with a 1 us switch interval)."""
    import sys
    import threading

    from robomodel.runtime.msg.types.std_srvs import Trigger

    ctx = Context()
    failures: list[BaseException] = []
    done = threading.Event()

    def read() -> None:
        while not done.is_set():
            try:
                ctx.graph()
            except RuntimeError as exc:
                failures.append(exc)
                return

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # the threads take turns as often as CPython lets them
    reader = threading.Thread(target=read)
    reader.start()
    try:
        for i in range(300):
            node = ctx.create_node(f"node_{i}")
            node.create_publisher(Float64, f"/topic_{i}")
            node.create_subscription(Float64, f"/topic_{i}", lambda _: None)
            node.create_service(Trigger, f"service_{i}", lambda _: Trigger.Response())
            node.destroy()
            if failures:
                break
    finally:
        done.set()
        reader.join(scaled(10))
        sys.setswitchinterval(interval)
    assert failures == []
