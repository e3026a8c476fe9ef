"""rospy's pieces that need no master: command-line remappings and name resolution (against
rosgraph's rules), genpy's Time and Duration (against Debian's genpy), handler answers as
responses, logging before init_node, and what is not offered."""

from __future__ import annotations

import importlib.util
import itertools
import math
import operator
import threading
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

import robomodel.clientlibs.rospy as rospy
from robomodel.clientlibs import genpy
from robomodel.clientlibs.rospy import core
from robomodel.clientlibs.rospy.names import parse_command_line, resolve, resolve_remappings
from robomodel.clientlibs.rospy.service import response_of
from robomodel.runtime.msg.types.std_msgs import String
from tests.timing import scaled, wait_until

GENPY_ROSTIME = Path("/usr/lib/python3/dist-packages/genpy/rostime.py")


def test_every_exported_name_resolves() -> None:
    for name in rospy.__all__:
        assert getattr(rospy, name) is not None, name
    for name in genpy.__all__:
        assert getattr(genpy, name) is not None, name


def test_command_line_as_rospy_reads_it() -> None:
    line = parse_command_line(
        ["prog", "chatter:=/words", "__name:=probe", "__ns:=/lab", "_rate:=5.5",
         "_on:=true", "_list:=[1, 2]", "_text:=hello", "__log:=/tmp/x", "plain", "a:=b:=c"]
    )  # fmt: skip
    assert dict(line.remappings) == {"chatter": "/words"}
    assert dict(line.special) == {"__name": "probe", "__ns": "/lab", "__log": "/tmp/x"}
    assert dict(line.params) == {"rate": 5.5, "on": True, "list": [1, 2], "text": "hello"}
    assert rospy.myargv(["prog", "x:=y", "keep", "_p:=1"]) == ["prog", "keep"]


@pytest.mark.parametrize(
    ("name", "caller", "expected"),
    [
        ("chatter", "/talker", "/chatter"),
        ("chatter", "/lab/talker", "/lab/chatter"),
        ("~gain", "/lab/talker", "/lab/talker/gain"),
        ("/abs//olute/", "/lab/talker", "/abs/olute"),
        ("", "/lab/talker", "/lab/"),
        ("a/b", "/x/y/talker", "/x/y/a/b"),
    ],
)
def test_names_resolve_as_rosgraph(name: str, caller: str, expected: str) -> None:
    assert resolve(name, caller) == expected


def test_remappings_resolve_both_sides_for_the_node() -> None:
    remappings = resolve_remappings({"chatter": "words", "~in": "/raw", "/x": "~y"}, "/lab/node")
    assert remappings == {"/lab/chatter": "/lab/words", "/lab/node/in": "/raw", "/x": "/lab/node/y"}
    assert resolve("chatter", "/lab/node", remappings) == "/lab/words"
    assert resolve("~in", "/lab/node", remappings) == "/raw"
    assert resolve("other", "/lab/node", remappings) == "/lab/other"


@pytest.fixture(scope="module")
def debian_genpy() -> ModuleType:
    if not GENPY_ROSTIME.exists():
        pytest.fail(f"Debian's genpy is missing ({GENPY_ROSTIME}): tools/system-deps test")
    spec = importlib.util.spec_from_file_location("debian_genpy_rostime", GENPY_ROSTIME)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _same(ours: Any, theirs: Any) -> None:
    if isinstance(theirs, (int, float, bool)):
        assert ours == theirs or (math.isnan(ours) and math.isnan(theirs))
        return
    if isinstance(theirs, tuple):
        for a, b in zip(ours, theirs, strict=True):
            _same(a, b)
        return
    assert type(ours).__name__ == type(theirs).__name__, (ours, theirs)
    assert (ours.secs, ours.nsecs) == (theirs.secs, theirs.nsecs), (ours, theirs)
    assert repr(ours) == repr(theirs) and str(ours) == str(theirs)


VALUES = [(0, 0), (1, 5), (2, 1_999_999_999), (-1, 0), (-3, -700_000_000), (1.5, 0), (0.3, 0),
          (-2.25, 0), (1_700_000_000, 123_456_789)]  # fmt: skip
BINARY = [operator.add, operator.sub, operator.lt, operator.le, operator.gt, operator.ge,
          operator.eq, operator.ne]  # fmt: skip
SCALARS = [2, -3, 0.5, 1.25]


def test_time_and_duration_as_debians_genpy(debian_genpy: ModuleType) -> None:
    def make(module: Any, kind: str, value: tuple[Any, Any]) -> Any:
        try:
            return getattr(module, kind)(*value)
        except (TypeError, ValueError) as exc:
            return type(exc)

    pairs = []
    for kind, value in itertools.product(("Time", "Duration"), VALUES):
        ours, theirs = make(genpy, kind, value), make(debian_genpy, kind, value)
        if isinstance(theirs, type):
            assert ours is theirs, (kind, value)
            continue
        _same(ours, theirs)
        assert (ours.to_sec(), ours.to_nsec(), bool(ours)) == (
            theirs.to_sec(), theirs.to_nsec(), bool(theirs),
        )  # fmt: skip
        assert hash(ours) == hash(theirs)
        pairs.append((ours, theirs))
    for (a, ta), (b, tb) in itertools.product(pairs, repeat=2):
        for op in BINARY:
            try:
                expected: Any = op(ta, tb)
            except TypeError:
                with pytest.raises(TypeError):
                    op(a, b)
                continue
            _same(op(a, b), expected)
    for a, ta in pairs:
        if isinstance(ta, debian_genpy.Duration):
            _same(-a, -ta)
            _same(abs(a), abs(ta))
            for k in SCALARS:
                _same(a * k, ta * k)
                _same(a / k, ta / k)
                _same(a // k, ta // k)
            for b, tb in pairs:
                if isinstance(tb, debian_genpy.Duration) and tb.to_nsec():
                    _same(a / b, ta / tb)
                    _same(a // b, ta // tb)
                    _same(a % b, ta % tb)
                    _same(divmod(a, b), divmod(ta, tb))
    for seconds in (0.0, 0.1, 1.999999999, 1e9 + 0.5):
        _same(genpy.Time.from_sec(seconds), debian_genpy.Time.from_sec(seconds))
        _same(genpy.Duration.from_sec(-seconds), debian_genpy.Duration.from_sec(-seconds))


def test_rospy_time_is_genpys_with_now() -> None:
    assert issubclass(rospy.Time, genpy.Time) and issubclass(rospy.Duration, genpy.Duration)
    later = rospy.Time(10) + rospy.Duration(2, 500)
    assert type(later) is rospy.Time and later.to_nsec() == 12_000_000_500
    assert repr(rospy.Duration.from_sec(1.5)) == "rospy.Duration[1500000000]"
    with pytest.raises(rospy.ROSInitException, match="init_node"):
        rospy.Time.now()


def test_every_robomodel_message_is_a_genpy_message() -> None:
    assert isinstance(String(data="x"), genpy.Message)
    assert not isinstance("x", genpy.Message) and not issubclass(str, genpy.Message)


def test_handler_answers_become_responses_as_rospy_reads_them() -> None:
    from robomodel.runtime.msg.schema import get_service_type

    response = get_service_type("std_srvs/srv/SetBool").Response
    assert response_of(response(True, "ok"), response).message == "ok"
    assert response_of({"success": True, "message": "kw"}, response).message == "kw"
    assert response_of((True, "pos"), response).message == "pos"
    assert response_of(True, response).success is True
    with pytest.raises(rospy.ServiceException, match="service handler returned None"):
        response_of(None, response)
    with pytest.raises(rospy.ServiceException, match="handler returned invalid value"):
        response_of({"nonsense": 1}, response)


def test_logging_forms_before_init_node(capsys: pytest.CaptureFixture[str]) -> None:
    for i in range(3):
        rospy.loginfo_once("once %d", i)
        rospy.logwarn_throttle(60, f"throttled {i}")
        rospy.logerr_throttle_identical(60, "same")
        rospy.logerr_throttle_identical(60, f"differs {i}")
        rospy.logdebug("hidden at the default level")
    out, err = capsys.readouterr()
    assert [line.split("]: ", 1)[1] for line in out.splitlines()] == ["once 0"]
    assert out.startswith("[INFO] [")
    assert [line.split("]: ", 1)[1] for line in err.splitlines()] == [
        "throttled 0", "same", "differs 0", "differs 1", "differs 2",
    ]  # fmt: skip
    assert err.startswith("[WARN] [")


def test_what_is_not_offered_raises_naming_it() -> None:
    for name, what in rospy.UNSUPPORTED.items():
        with pytest.raises(NotImplementedError, match=r"is not offered by robomodel's rospy"):
            getattr(rospy, name)()
        assert what in repr(getattr(rospy, name))
    with pytest.raises(AttributeError, match="no attribute 'nonsense'"):
        rospy.nonsense  # noqa: B018


def test_before_init_node_the_node_is_unnamed() -> None:
    assert core.current() is None
    assert rospy.get_name().endswith("/unnamed")
    with pytest.raises(rospy.ROSInitException, match=r"call rospy.init_node\(name\) first"):
        rospy.robomodel_node()
    with pytest.raises(rospy.ROSInitException):
        rospy.get_param("x")


def test_a_message_face_of_time_is_a_genpy_time() -> None:
    """A genpy-flavoured message's stamp (a face of builtin_interfaces/msg/Time with genpy's
    ``secs``/``nsecs``) is a ``genpy.Time``: it compares and subtracts with rospy's times."""

    class FaceTime:
        __typename__ = "builtin_interfaces/msg/Time"

        def __init__(self, secs: int, nsecs: int) -> None:
            self.secs, self.nsecs = secs, nsecs

        def to_nsec(self) -> int:
            return self.secs * 1_000_000_000 + self.nsecs

    stamp = FaceTime(5, 250)
    assert isinstance(stamp, genpy.Time) and not isinstance(stamp, genpy.Duration)
    assert not isinstance(stamp, rospy.Time)  # rospy's subclass stays rospy's
    assert (rospy.Time(7, 250) - stamp).to_sec() == 2.0  # type: ignore[operator]
    assert rospy.Time(5, 250) == stamp and rospy.Time(4) < stamp
    from robomodel.runtime.msg import Time as OwnTime

    assert not isinstance(OwnTime(1, 2), genpy.Time)  # sec/nanosec, no genpy fields


@pytest.fixture
def manual_node() -> Any:
    """A rospy node state on the in-process bus with a manual clock (no master), removed
    after the test."""
    from robomodel.runtime.clock import ManualClock
    from robomodel.runtime.context import Context

    clock = ManualClock(100.0)
    context = Context("inproc", clock=clock)
    node = context.create_node("timing")
    core.set_state(core.NodeState("/timing", {}, context, node))
    try:
        yield context, clock
    finally:
        core._LIFE.state = None
        context.shutdown()


def _advance_in_background(
    clock: Any, step_s: float, until_s: float | None = None
) -> tuple[Any, Any]:
    """A thread moving ``clock`` on by ``step_s`` every 2 ms of wall time, to exactly
    ``until_s`` (then it stops), or until the event returned with it is set. A sleeper
    waiting for a time up to ``until_s`` wakes at it however late it is scheduled: the clock
    waits there."""
    import threading
    import time

    stop = threading.Event()

    def run() -> None:
        while not stop.is_set():
            time.sleep(0.002)
            now_s = clock.now_s()
            if until_s is not None and now_s + step_s >= until_s - 1e-9:
                clock.set(until_s)
                return
            clock.set(now_s + step_s)

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    return thread, stop


def test_rate_and_sleep_follow_ros_time(manual_node: Any) -> None:
    _, clock = manual_node
    rate = rospy.Rate(10)
    assert rate.last_time == rospy.Time(100)
    assert rate.remaining() == rospy.Duration(0, 100_000_000)
    for tick in range(1, 4):
        mover, _ = _advance_in_background(clock, 0.01, until_s=100.0 + 0.1 * tick)
        rate.sleep()
        mover.join()
        assert clock.now_s() == pytest.approx(100.0 + 0.1 * tick)
        assert rate.last_time.to_sec() == pytest.approx(100.0 + 0.1 * tick)
    clock.set(clock.now_s() + 5.0)  # a loop far behind starts its schedule afresh
    late_s = clock.now_s()
    rate.sleep()
    assert rate.last_time.to_sec() == pytest.approx(late_s)
    start_s = clock.now_s()
    mover, stop = _advance_in_background(clock, 0.01)
    try:
        rospy.sleep(0.05)
        assert clock.now_s() >= start_s + 0.05 - 1e-9
    finally:
        stop.set()
        mover.join()
    rospy.sleep(rospy.Duration(-1))  # a negative sleep returns at once


def test_timer_events_in_ros_time(manual_node: Any) -> None:
    _, clock = manual_node
    events: list[Any] = []
    once: list[Any] = []
    timer = rospy.Timer(rospy.Duration(0.5), events.append)
    oneshot = rospy.Timer(rospy.Duration(0.25), once.append, oneshot=True)
    assert timer.is_alive() and timer is not threading.current_thread()  # a thread, as rospy's
    for step in range(1, 17):  # to 101.6 in steps of 0.1 s, each tick waited for
        clock.set(100.0 + 0.1 * step)
        due = (int(0.1 * step / 0.5 + 1e-9), int(step >= 3))
        wait_until(
            lambda due=due: (len(events), len(once)) == due,  # type: ignore[misc]
            scaled(5),
            what=f"the timers' calls at {clock.now_s():.1f} s",
        )
    assert [e.current_expected.to_sec() for e in events] == [100.5, 101.0, 101.5]
    assert events[0].last_expected is None and events[0].last_duration is None
    assert events[2].last_expected == events[1].current_expected
    assert events[2].last_real == events[1].current_real
    assert events[1].current_real.to_sec() == pytest.approx(101.0)
    assert len(once) == 1 and once[0].current_real.to_sec() == pytest.approx(100.3)
    wait_until(lambda: not oneshot.is_alive(), scaled(5), what="the oneshot timer's end")
    timer.shutdown()
    clock.set(102.1)  # the timer's next tick: it ends there without calling
    wait_until(lambda: not timer.is_alive(), scaled(5), what="the timer's end")
    assert len(events) == 3
