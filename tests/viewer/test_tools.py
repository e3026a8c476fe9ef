"""The rqt tools' logic: field paths, expressions, the publishers' messages, plot data, scans."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from robomodel.runtime.msg import (
    Float64,
    Float64MultiArray,
    Int32,
    JointControllerState,
    JointState,
    LaserScan,
    Odometry,
    Twist,
    get_message_type,
)
from robomodel.viewer.displays.laser_scan import scan_points
from robomodel.viewer.tools import (
    Expression,
    ExpressionError,
    ExpressionPublisher,
    FieldPathError,
    PlotData,
    SteeringCommand,
    field_value,
    parse_variables,
    resolve_field_path,
    set_field,
)

TOPICS = {
    "/joint_states": JointState,
    "/joint1_position_controller/state": JointControllerState,
    "/joint1_position_controller/command": Float64,
    "/odom": Odometry,
}


def test_field_paths_resolve_to_the_longest_topic_as_rqt_plot() -> None:
    path = resolve_field_path("/joint1_position_controller/state/process_value", TOPICS)
    assert path.topic == "/joint1_position_controller/state"
    assert path.steps == ("process_value",)
    path = resolve_field_path("/joint_states/position[1]", TOPICS)
    assert (path.topic, path.steps, path.text) == (
        "/joint_states",
        ("position", 1),
        "/joint_states/position[1]",
    )
    path = resolve_field_path("odom/pose/pose/position/x", TOPICS)
    assert path.steps == ("pose", "pose", "position", "x") and path.msg_type is Odometry
    assert resolve_field_path("/joint1_position_controller/command/data", TOPICS).msg_type is (
        Float64
    )


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("/nothere/data", "no known topic is a prefix"),
        ("/odom/pose/pose/positon/x", "did you mean position"),
        ("/joint_states/position", "add an index, e.g. /joint_states/position[0]"),
        ("/joint_states/name[0]", "is a string"),
        ("/odom/pose/pose", "add one of its fields: position, orientation"),
        ("/odom/pose/covariance[36]", "past the array's 36"),
        ("/joint_states", "add a field of sensor_msgs/msg/JointState"),
        ("/odom/child_frame_id[0]", "not an array"),
    ],
)
def test_field_path_errors_say_what_is_valid(text: str, message: str) -> None:
    with pytest.raises(FieldPathError, match=re.escape(message)):
        resolve_field_path(text, TOPICS)


def test_field_values_from_messages() -> None:
    states = JointState(name=["a", "b"], position=[0.5, -1.25])
    assert field_value(states, ("position", 1)) == -1.25
    assert field_value(states, ("position", 2)) is None  # shorter in this message: no sample
    odom = Odometry()
    odom.pose.pose.position.x = 3.0
    assert field_value(odom, ("pose", "pose", "position", "x")) == 3.0


def test_set_field_builds_messages_with_defaults_elsewhere() -> None:
    twist = set_field(Twist, ("angular", "z"), 0.7)
    assert isinstance(twist, Twist) and twist.angular.z == 0.7 and twist.linear.x == 0.0
    array = set_field(Float64MultiArray, ("data", 2), 4.0)
    assert isinstance(array, Float64MultiArray) and array.data == [0.0, 0.0, 4.0]
    integer = set_field(Int32, ("data",), 2.6)
    assert isinstance(integer, Int32) and integer.data == 3
    with pytest.raises(FieldPathError):
        set_field(Twist, ("linear",), 1.0)
    image_type = get_message_type("sensor_msgs/msg/Image")
    image = set_field(image_type, ("data", 2), 7.2)  # uint8[] is bytes: grown all the same
    assert bytes(image.data) == b"\x00\x00\x07"  # type: ignore[attr-defined]
    with pytest.raises(FieldPathError, match="out of range"):
        set_field(image_type, ("data", 0), 256.0)


def test_seed_expression_as_rqt_publisher() -> None:
    variables = parse_variables("speed=1, diff=(pi - -pi)/2; offset=pi - diff")
    assert variables == {"speed": 1.0, "diff": pytest.approx(math.pi), "offset": 0.0}
    expr = Expression("sin(i/rate*speed)*diff + offset", ("i", "rate", "t", *variables))
    for i in (0, 7, 50, 123):
        value = expr.evaluate({"i": i, "rate": 50.0, "t": i / 50.0, **variables})
        assert value == pytest.approx(math.sin(i / 50.0) * math.pi)
    assert Expression("1 if sin(t) > 0 else -1").evaluate({"i": 0, "rate": 1, "t": 4}) == -1.0
    assert Expression("max(0, min(1, t)) + abs(-2)").evaluate({"t": 0.5}) == 2.5


@pytest.mark.parametrize(
    "text",
    [
        "__import__('os').system('true')",
        "().__class__.__bases__",
        "open('/etc/passwd')",
        "sin.__self__",
        "'text'",
        "lambda: 1",
        "[1, 2][0]",
        "sin(x=1)",
        "(lambda: 0)()",
        "eval('1')",
        "i.real",
        "speed",
        "True + 1",
    ],
)
def test_expressions_refuse_anything_but_arithmetic(text: str) -> None:
    with pytest.raises(ExpressionError):
        Expression(text)


def test_expression_errors_at_evaluation_are_expression_errors() -> None:
    with pytest.raises(ExpressionError, match=r"range|overflow|large"):
        Expression("10**10**10").evaluate({})
    with pytest.raises(ExpressionError):
        Expression("log(i)").evaluate({"i": 0.0})
    with pytest.raises(ExpressionError, match="did you mean sin"):
        Expression("sine(t)")
    with pytest.raises(ExpressionError, match="name=value"):
        parse_variables("speed 1")


def test_expression_publisher_messages_follow_the_counter() -> None:
    pub = ExpressionPublisher("std_msgs/Float64", "data", "sin(i/50)*3.1415", 50.0)
    values = [pub.next_message() for _ in range(3)]
    assert all(isinstance(m, Float64) for m in values)
    assert [m.data for m in values] == pytest.approx(  # type: ignore[attr-defined]
        [math.sin(i / 50) * 3.1415 for i in range(3)]
    )
    twist = ExpressionPublisher("geometry_msgs/msg/Twist", "linear/x", "t", 10.0)
    twist.next_message()
    msg = twist.next_message()
    assert isinstance(msg, Twist) and msg.linear.x == pytest.approx(0.1)
    with pytest.raises(FieldPathError):
        ExpressionPublisher("std_msgs/msg/Float64", "value", "1", 10.0)
    with pytest.raises(ExpressionError):
        ExpressionPublisher("std_msgs/msg/Float64", "data", "x + 1", 10.0)


def test_steering_sends_zero_once_as_rqt_robot_steering() -> None:
    command = SteeringCommand()
    first = command.twist(0.0, 0.0)
    assert first is not None and first.linear.x == 0.0
    assert command.twist(0.0, 0.0) is None  # other sources may take over
    moving = command.twist(0.5, -1.0)
    assert moving is not None and (moving.linear.x, moving.angular.z) == (0.5, -1.0)
    assert command.twist(0.5, -1.0) is not None  # re-sent every tick while non-zero
    assert command.twist(0.0, 0.0) is not None
    assert command.twist(0.0, 0.0) is None


def test_plot_window_interpolates_series_on_one_time_axis() -> None:
    data = PlotData(lambda: 1000.0)
    t0 = data.start_s
    command = data.add(resolve_field_path("/joint1_position_controller/command/data", TOPICS))
    state = data.add(resolve_field_path("/joint_states/position[0]", TOPICS))
    assert [a.size for a in data.window(10.0, t0 + 1.0)] == [0, 0, 0]  # no samples yet
    data.record(command, Float64(1.0), t0 + 1.0)
    for k in range(5):
        data.record(state, JointState(position=[0.1 * k]), t0 + 1.0 + 0.5 * k)
    x, cmd, pos = data.window(10.0, t0 + 3.0)
    assert x.tolist() == [1.0, 1.5, 2.0, 2.5, 3.0]
    assert cmd.tolist() == [1.0] * 5  # held after its one sample
    assert pos.tolist() == pytest.approx([0.0, 0.1, 0.2, 0.3, 0.4])
    x, _, pos = data.window(1.0, t0 + 3.0)  # the moving window: the last second only
    assert x.tolist() == [2.0, 2.5, 3.0]


def test_plot_x_is_rqt_plot_s_seconds_since_the_plot_started_on_ros_time() -> None:
    """rqt_plot: x = (header stamp, else arrival) - the plot's start, on ROS time; Clear keeps
    the start. A zero stamp or one from another clock (a simulator's stamps beside a wall
    clock) is placed at its arrival."""
    clock = [120.0]  # ROS time [s], e.g. simulated seconds under use_sim_time
    data = PlotData(lambda: clock[0])
    clock[0] = 130.0  # the series is added ten seconds after the plot started
    state = data.add(resolve_field_path("/joint_states/position[0]", TOPICS))
    stamped = JointState(position=[1.0])
    stamped.header.stamp.sec, stamped.header.stamp.nanosec = 129, 500_000_000
    data.record(state, stamped)  # arrives at 130, taken at 129.5
    data.record(state, JointState(position=[2.0]))  # stamp 0: its arrival, 130
    elsewhere = JointState(position=[3.0])
    elsewhere.header.stamp.sec = 1_700_000_000  # wall time while the plot runs on sim time
    clock[0] = 131.0
    data.record(state, elsewhere)
    command = data.add(resolve_field_path("/joint1_position_controller/command/data", TOPICS))
    data.record(command, Float64(5.0))  # no header: its arrival, 131
    assert list(state.times_s) == [9.5, 10.0, 11.0] and list(command.times_s) == [11.0]
    x, *_ = data.window(10.0)
    assert x.tolist() == [11.0]  # from the moment every series has a sample
    data.clear()
    assert data.series == [] and data.start_s == 120.0


def test_scan_points_drop_invalid_ranges() -> None:
    scan = LaserScan(
        angle_min=0.0,
        angle_increment=math.pi / 2,
        range_min=0.1,
        range_max=5.0,
        ranges=[1.0, float("inf"), 2.0, 0.05, 9.0],
    )
    points = scan_points(scan)
    assert points == pytest.approx(np.array([[1.0, 0.0, 0.0], [-2.0, 0.0, 0.0]]), abs=1e-12)


def test_messages_are_shown_literally_in_markdown() -> None:
    from robomodel.viewer.markup import escape_markdown

    assert escape_markdown("sin(i/rate*speed)*diff [pid_p]") == (
        r"sin(i/rate\*speed)\*diff \[pid\_p\]"
    )


def test_steering_follows_a_diff_drive_topic_until_edited() -> None:
    from types import SimpleNamespace

    from robomodel.viewer.tools.steering import SteeringTool

    tool = SteeringTool.__new__(SteeringTool)
    tool.topic = SimpleNamespace(value="/cmd_vel")
    twist = {"geometry_msgs/msg/Twist"}
    tool.follow_graph({"/odom": {"nav_msgs/msg/Odometry"}, "/simplebot_controller/cmd_vel": twist})
    assert tool.topic.value == "/simplebot_controller/cmd_vel"
    tool.topic.value = "/my_robot/cmd_vel"  # edited by the user: kept
    tool.follow_graph({"/other/cmd_vel": twist})
    assert tool.topic.value == "/my_robot/cmd_vel"
    fresh = SteeringTool.__new__(SteeringTool)
    fresh.topic = SimpleNamespace(value="/cmd_vel")
    fresh.follow_graph({"/cmd_vel": twist, "/x/cmd_vel": twist})  # /cmd_vel is in use: kept
    assert fresh.topic.value == "/cmd_vel"


class _Control:
    def __init__(self, value: object) -> None:
        self.value, self.min, self.max = value, -1.0, 1.0
        self.callbacks: list[object] = []

    def on_update(self, callback: object) -> None:
        self.callbacks.append(callback)

    on_click = on_update

    def moved_by_page(self, value: float) -> None:
        from types import SimpleNamespace

        self.value = value
        for callback in self.callbacks:
            callback(SimpleNamespace(client=object()))  # type: ignore[operator]


class _SteeringGui:
    def __getattr__(self, name: str) -> object:
        def add(_label: str, value: object = None, **kwargs: object) -> _Control:
            return _Control(kwargs.get("initial_value", value))

        return add


def test_steering_is_a_dead_man_switch_when_the_last_page_leaves() -> None:
    """A page drives at 0.5 m/s and closes: one zero command, then nothing, also if the
    program sets a slider, until a page moves a slider again."""
    from types import SimpleNamespace

    from robomodel.viewer.tools.steering import SteeringTool

    sent: list[object] = []
    clients: dict[int, object] = {}
    node = SimpleNamespace(
        create_publisher=lambda *_a: SimpleNamespace(publish=sent.append, destroy=lambda: None),
        create_timer=lambda *_a: None,
    )
    server = SimpleNamespace(gui=_SteeringGui(), get_clients=lambda: dict(clients))
    tools = SimpleNamespace(server=server, node=node, post=lambda f: f())
    tool = SteeringTool(tools)  # type: ignore[arg-type]
    clients[1] = object()  # a page connects and moves the slider
    tool.linear.moved_by_page(0.5)  # type: ignore[attr-defined]
    for _ in range(3):
        tool.tick()
    assert [t.linear.x for t in sent] == [0.5, 0.5, 0.5]  # type: ignore[attr-defined]
    clients.clear()  # the last page leaves
    for _ in range(5):
        tool.tick()
    assert [t.linear.x for t in sent[3:]] == [0.0]  # type: ignore[attr-defined]
    assert tool.linear.value == 0.0 and not tool.armed
    tool.linear.value = 0.7  # set by a program, not a page: still nothing
    tool.tick()
    clients[2] = object()  # a page opens: nothing until it moves a slider
    tool.tick()
    assert len(sent) == 4
    tool.angular.moved_by_page(-1.0)  # type: ignore[attr-defined]
    tool.tick()
    assert len(sent) == 5 and sent[-1].angular.z == -1.0  # type: ignore[attr-defined]


class _Folder:
    def __enter__(self) -> _Folder:
        return self

    def __exit__(self, *_args: object) -> None:
        return None

    def remove(self) -> None:
        return None


class _ParamGui(_SteeringGui):
    def add_folder(self, _label: str) -> _Folder:
        return _Folder()

    def add_markdown(self, content: str) -> _Control:
        return _Control(content)


def test_a_node_of_many_parameters_shows_the_first_thousand() -> None:
    import time

    from robomodel.viewer.limits import MAX_PARAMETERS_SHOWN
    from robomodel.viewer.markup import safe_markdown
    from robomodel.viewer.tools.params import ParameterTool
    from tests.timing import scaled

    tool = ParameterTool.__new__(ParameterTool)
    tool.gui = _ParamGui()
    tool.result = safe_markdown(tool.gui)
    tool._folder, tool._parent, tool.controls = None, _Folder(), {}
    values = {f"p{k:07d}": float(k) for k in range(10**5)}
    start = time.perf_counter()
    tool._build("/flood", values)
    assert time.perf_counter() - start < scaled(5.0)
    assert len(tool.controls) == MAX_PARAMETERS_SHOWN == 1000
    assert sorted(tool.controls)[-1] == "p0000999"  # the first by name
    assert tool.result.content == "100000 parameter(s) of `/flood`; the first 1000 shown"
