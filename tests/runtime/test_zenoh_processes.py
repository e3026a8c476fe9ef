"""Several processes over Zenoh on loopback: topics, latching, graph, parameters, SIGINT.

Each test uses its own domain id so tests can run in parallel.
"""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import ROBOMODEL, unique_domain
from tests.timing import scaled, wait_until

TALKER = textwrap.dedent(
    """
    import faulthandler, signal, sys
    faulthandler.register(signal.SIGUSR1, all_threads=True)  # the test asks for stacks on a hang
    from robomodel.runtime import Context, latched
    from robomodel.runtime.msg import Float64, String
    ctx = Context("zenoh", domain_id=int(sys.argv[1]))
    node = ctx.create_node("talker")
    node.declare_parameter("gain", 1.5)
    pub = node.create_publisher(Float64, "/chatter")
    node.create_publisher(String, "/robot_description", latched()).publish(String("<robot/>"))
    count = [0]
    def tick():
        count[0] += 1
        pub.publish(Float64(count[0] * node.get_parameter("gain")))
    node.create_timer(0.05, tick)
    print("ready", flush=True)
    try:
        ctx.spin()
    except KeyboardInterrupt:
        pass
    ctx.shutdown()
    print("clean exit", flush=True)
    """
)


def _domain(_offset: int = 0) -> str:
    return unique_domain()


@pytest.fixture
def talker(tmp_path: Path) -> Iterator[tuple[subprocess.Popen[str], str]]:
    script = tmp_path / "talker.py"
    script.write_text(TALKER)
    domain = _domain(1)
    proc = subprocess.Popen(
        [sys.executable, str(script), domain],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert proc.stdout is not None and proc.stdout.readline().strip() == "ready"
    yield proc, domain
    if proc.poll() is None:
        proc.kill()
        proc.wait()


def _cli(*args: str, timeout: float = 20) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*ROBOMODEL, *args], capture_output=True, text=True, timeout=scaled(timeout)
    )


def test_echo_info_list_across_processes(talker: tuple[subprocess.Popen[str], str]) -> None:
    _, domain = talker
    echo = _cli("topic", "echo", "/chatter", "--count", "3", "--domain-id", domain)
    assert echo.returncode == 0, echo.stderr
    docs = [d for d in echo.stdout.split("---\n") if d.strip()]
    assert len(docs) == 3 and all(d.startswith("data: ") for d in docs)
    values = [float(d.split()[1]) for d in docs]
    assert values == sorted(values) and values[1] - values[0] == pytest.approx(1.5)
    latched = _cli("topic", "echo", "/robot_description", "--once", "--domain-id", domain)
    assert latched.stdout == "data: <robot/>\n---\n"
    listing = _cli("topic", "list", "-t", "--domain-id", domain)
    assert "/chatter [std_msgs/msg/Float64]" in listing.stdout.splitlines()
    info = _cli("topic", "info", "/chatter", "--domain-id", domain)
    assert info.stdout.startswith("Type: std_msgs/msg/Float64\nPublisher count: 1\n")


def test_echo_s_timeout_bounds_the_wait_for_the_topic_s_type() -> None:
    # without a type, echo waits up to 5 s for a publisher to name it; --timeout ends it sooner
    domain = unique_domain()
    try:
        echo = _cli(
            "topic",
            "echo",
            "/nobody",
            "--once",
            "--timeout",
            "0.5",
            "--domain-id",
            domain,
            timeout=4,
        )
    except subprocess.TimeoutExpired:
        pytest.fail("topic echo --timeout 0.5 was still waiting for a publisher after 4 s")
    assert echo.returncode == 2
    assert "could not determine the type of /nobody: no publisher found" in echo.stderr


def test_parameters_across_processes(
    talker: tuple[subprocess.Popen[str], str], tmp_path: Path
) -> None:
    _, domain = talker
    assert (
        _cli("param", "get", "/talker", "gain", "--domain-id", domain).stdout
        == "Double value is: 1.5\n"
    )
    assert (
        _cli("param", "set", "talker", "gain", "2", "--domain-id", domain).stdout
        == "Set parameter successful\n"
    )
    dumped = _cli("param", "dump", "/talker", "--domain-id", domain).stdout
    assert "gain: 2.0" in dumped and dumped.startswith("/talker:\n  ros__parameters:\n")
    refused = _cli("param", "set", "talker", "gain", "fast", "--domain-id", domain)
    assert refused.returncode == 1 and "Setting parameter failed" in refused.stdout
    params = tmp_path / "p.yaml"
    params.write_text("talker:\n  ros__parameters:\n    gain: 3.0\n")
    loaded = _cli("param", "load", "/talker", str(params), "--domain-id", domain)
    assert loaded.stdout == "Set parameter gain successful\n"
    echo = _cli("topic", "echo", "/chatter", "--count", "2", "--domain-id", domain)
    values = [float(d.split()[1]) for d in echo.stdout.split("---\n") if d.strip()]
    assert values[1] - values[0] == pytest.approx(3.0)
    missing = _cli("param", "get", "/nobody", "x", "--domain-id", domain)
    assert missing.returncode == 2 and "has no server on the bus" in missing.stderr


def _wait_subscribed(domain: str, topic: str) -> None:
    """Until another process's subscription to ``topic`` is in the graph."""
    from robomodel.runtime import Context

    with Context("zenoh", domain_id=int(domain)) as ctx:

        def subscribed() -> bool:
            info = ctx.graph().topics.get(topic)
            return info is not None and bool(info.subscribers)

        wait_until(subscribed, 20, what=f"a subscription to {topic}")


def test_pub_reaches_a_subscriber_in_another_process(tmp_path: Path) -> None:
    domain = _domain(2)
    echo = subprocess.Popen(
        [
            *ROBOMODEL,
            "topic",
            "echo",
            "/cmd",
            "geometry_msgs/msg/Twist",
            "--once",
            "--domain-id",
            domain,
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    _wait_subscribed(domain, "/cmd")
    pub = _cli(
        "topic",
        "pub",
        "/cmd",
        "geometry_msgs/Twist",
        "{linear: {x: 0.2}, angular: {z: 0.5}}",
        "--once",
        "--domain-id",
        domain,
    )
    assert pub.returncode == 0, pub.stderr
    assert pub.stdout.startswith(
        "publisher: beginning loop\npublishing #1: geometry_msgs.msg.Twist("
    )
    out, _ = echo.communicate(timeout=scaled(20))
    assert "linear:\n  x: 0.2\n" in out and "angular:\n  x: 0.0\n  y: 0.0\n  z: 0.5\n" in out


def test_domains_are_isolated(talker: tuple[subprocess.Popen[str], str]) -> None:
    assert talker[0].poll() is None  # publishing /chatter on its own domain
    other = unique_domain()  # not the talker's id + k: that may be another worker's, in use
    echo = _cli(
        "topic",
        "echo",
        "/chatter",
        "std_msgs/msg/Float64",
        "--once",
        "--timeout",
        "1.5",
        "--domain-id",
        other,
    )
    assert echo.returncode == 1 and echo.stdout == ""


def _lines_until(stream: Any, text: str, timeout_s: float) -> list[str]:
    """The lines of ``stream`` up to and including the first that holds ``text``, read on a
    thread of their own for at most ``scaled(timeout_s)``: what was read by then."""
    lines: list[str] = []

    def read() -> None:
        for line in iter(stream.readline, ""):
            lines.append(line)
            if text in line:
                return

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    reader.join(scaled(timeout_s))
    return list(lines)


def test_sigint_exits_cleanly(talker: tuple[subprocess.Popen[str], str]) -> None:
    proc, domain = talker
    echo = subprocess.Popen(
        [*ROBOMODEL, "topic", "echo", "/chatter", "--domain-id", domain],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    # Interrupt once echo is running (its first message printed): a process still importing
    # when Ctrl-C comes ends as Python does before any handler exists, on a loaded machine too.
    assert echo.stdout is not None
    first = _lines_until(echo.stdout, "data:", 60)
    assert any("data:" in line for line in first), "topic echo printed no message in 60 s"
    for p in (echo, proc):
        p.send_signal(signal.SIGINT)
    _out, err = echo.communicate(timeout=scaled(10))
    assert echo.returncode == 0 and "Traceback" not in err
    try:
        t_out, t_err = proc.communicate(timeout=scaled(10))
    except subprocess.TimeoutExpired:
        proc.send_signal(signal.SIGUSR1)  # faulthandler: every thread's stack to stderr
        try:
            t_out, t_err = proc.communicate(timeout=scaled(5))
        except subprocess.TimeoutExpired:
            proc.kill()
            t_out, t_err = proc.communicate()
        raise AssertionError(f"the talker did not exit on SIGINT:\n{t_out}\n{t_err}") from None
    assert proc.returncode == 0 and "clean exit" in t_out and "Traceback" not in t_err


def test_bad_type_and_yaml_are_clear_errors() -> None:
    bad_type = _cli(
        "topic", "pub", "/x", "std_msgs/msg/Float46", "data: 1", "--once", "--bus", "inproc"
    )
    assert (
        bad_type.returncode == 2
        and "unknown message type" in bad_type.stderr
        and "Traceback" not in bad_type.stderr
    )
    bad_yaml = _cli(
        "topic", "pub", "/x", "std_msgs/msg/Float64", "data: [", "--once", "--bus", "inproc"
    )
    assert bad_yaml.returncode == 2 and "invalid YAML" in bad_yaml.stderr
    misfit = _cli("topic", "pub", "/x", "std_msgs/Float64", "value: 1", "--once", "--bus", "inproc")
    assert misfit.returncode == 2 and "has no field 'value'" in misfit.stderr


def test_seed_workflow_three_processes() -> None:
    """publish-state in one process, topic echo and live tf in others; live tf == static tf."""
    from tests.conftest import EXAMPLES

    urdf = str(EXAMPLES / "gripper_description" / "urdf" / "planar_3dof.urdf")
    domain = _domain(3)
    state = subprocess.Popen(
        [*ROBOMODEL, "publish-state", urdf, "--domain-id", domain, "--duration", str(scaled(30))],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        echo = _cli("topic", "echo", "/joint_states", "--once", "--domain-id", domain)
        assert echo.returncode == 0, echo.stderr
        assert (
            "name:\n- joint_1\n- joint_2\n- joint_3\nposition:\n- 0.0\n- 0.0\n- 0.0\n"
            in echo.stdout
        )
        live = _cli("tf", "base_link", "gripper", "--once", "--domain-id", domain)
        assert live.returncode == 0, live.stderr
        static = _cli("tf", urdf, "base_link", "gripper")
        assert live.stdout.split("\n", 1)[1] == static.stdout.split("\n", 1)[1]  # all but the time
        assert live.stdout.startswith("At time ") and static.stdout.startswith("At time 0.0\n")
        description = _cli("topic", "echo", "/robot_description", "--once", "--domain-id", domain)
        assert "planar_3dof" in description.stdout
        frames = _cli("frames", "--live", "-t", "1.5", "--domain-id", domain)
        assert frames.returncode == 0, frames.stderr
        for edge in ('"base_link" -> "link_1"', '"link_1" -> "link_2"', '"link_2" -> "gripper"'):
            assert edge in frames.stdout
        assert "Broadcaster: default_authority" in frames.stdout
    finally:
        state.send_signal(signal.SIGINT)
        _, err = state.communicate(timeout=scaled(10))
    assert state.returncode == 0 and "Traceback" not in err


def test_malformed_payload_from_a_foreign_peer_is_dropped() -> None:
    """A peer that is not robomodel sends garbage on a topic: warned about, node keeps going."""
    from robomodel.runtime import Context
    from robomodel.runtime.msg import Float64

    domain = _domain(4)
    echo = subprocess.Popen(
        [
            *ROBOMODEL,
            "topic",
            "echo",
            "/chatter",
            "std_msgs/msg/Float64",
            "--once",
            "--domain-id",
            domain,
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    with Context("zenoh", domain_id=int(domain)) as ctx:
        session = ctx.transport.session  # type: ignore[attr-defined]
        deadline = time.monotonic() + scaled(20)
        while time.monotonic() < deadline:  # until the echo process's subscription is visible
            info = ctx.graph(timeout_s=scaled(0.3)).topics.get("/chatter")
            if info is not None and info.subscribers:
                break
            time.sleep(0.1)
        from robomodel.runtime.transport.rmw_zenoh import encode_attachment

        key = ctx.transport.data_key("/chatter", Float64)  # type: ignore[attr-defined]
        gid = bytes(range(16))
        session.put(key, b"\x00\x01\x00\x00\x01", attachment=encode_attachment(1, 0, gid))
        session.put(key, b"not cdr at all", attachment=encode_attachment(2, 0, gid))
        pub = ctx.create_node("good").create_publisher(Float64, "/chatter")
        deadline = time.monotonic() + scaled(20)
        while echo.poll() is None:  # echo --once exits at the first good message it gets
            assert time.monotonic() < deadline, "echo did not print the good message"
            pub.publish(Float64(2.5))
            time.sleep(0.2)
        out, err = echo.communicate(timeout=scaled(20))
    assert echo.returncode == 0 and out == "data: 2.5\n---\n"
    assert "dropping a malformed std_msgs/msg/Float64 payload on /chatter" in err
    assert "Traceback" not in err


def test_a_slow_subscriber_keeps_the_latest_depth_messages() -> None:
    """KEEP_LAST over Zenoh: a callback slower than the publisher drops the oldest samples
    (as DDS does) instead of building an ever-growing backlog; the newest one always arrives."""
    from robomodel.runtime import Context
    from robomodel.runtime.msg import Int32
    from robomodel.runtime.qos import QoSProfile

    domain = int(_domain(7))
    with (
        Context("zenoh", domain_id=domain) as sub_ctx,
        Context("zenoh", domain_id=domain) as pub_ctx,
    ):
        got: list[int] = []

        def slow(msg: Int32) -> None:
            time.sleep(0.02)
            got.append(msg.data)

        sub_ctx.create_node("slow").create_subscription(Int32, "/count", slow, QoSProfile(5))
        pub = pub_ctx.create_node("fast").create_publisher(Int32, "/count", 10)
        deadline = time.monotonic() + scaled(10)
        while (
            not pub_ctx.graph().topics.get("/count", None)
            or not pub_ctx.graph().topics["/count"].subscribers
        ):
            assert time.monotonic() < deadline
            time.sleep(0.05)
        time.sleep(0.3)
        for i in range(1, 201):  # 200 messages in well under the 4 s the callback would need
            pub.publish(Int32(i))
        deadline = time.monotonic() + scaled(10)
        while (not got or got[-1] != 200) and time.monotonic() < deadline:
            sub_ctx.spin_once(0.05)
        assert got and got[-1] == 200
        assert len(got) < 100 and got == sorted(got)


def test_a_late_subscriber_gets_every_latched_publishers_history() -> None:
    """/tf_static from two static broadcasters (robot_state_publisher and a simulator), and a
    depth-3 history: a subscriber that joins later receives all of it, as from DDS."""
    from robomodel.runtime import Context, latched
    from robomodel.runtime.msg import String

    domain = int(_domain())
    with Context("zenoh", domain_id=domain) as pub_ctx:
        node = pub_ctx.create_node("broadcasters")
        first = node.create_publisher(String, "/statics", latched())
        second = node.create_publisher(String, "/statics", latched(depth=3))
        first.publish(String("rsp: old"))
        first.publish(String("rsp"))
        for text in ("sim 1", "sim 2", "sim 3"):
            second.publish(String(text))
        # The subscriber's session opens after the publications: a session that is open
        # already may be sent a live sample before the routers know what it subscribes to,
        # and a subscription declared before that sample arrives receives it (as any live one).
        got: list[str] = []
        with Context("zenoh", domain_id=domain) as sub_ctx:
            sub_ctx.create_node("late").create_subscription(
                String, "/statics", lambda m: got.append(m.data), latched(depth=100)
            )
            deadline = time.monotonic() + scaled(10)
            while len(got) < 4 and time.monotonic() < deadline:
                sub_ctx.spin_once(0.05)
            sub_ctx.spin_once(0.3)
        assert sorted(got) == ["rsp", "sim 1", "sim 2", "sim 3"]
        assert [g for g in got if g.startswith("sim")] == ["sim 1", "sim 2", "sim 3"]


def test_latched_history_reaches_a_subscriber_after_the_first_process_left() -> None:
    """The first process on a domain links the others; when it exits (a short `robomodel tf`
    started before the simulator), a later subscriber still gets /tf_static once the
    publisher is reachable again, not only what is published after that."""
    from robomodel.runtime import Context, latched
    from robomodel.runtime.msg import String

    domain = int(_domain())
    first = Context("zenoh", domain_id=domain)  # takes the domain's anchor port
    with Context("zenoh", domain_id=domain) as pub_ctx:
        pub = pub_ctx.create_node("broadcaster").create_publisher(String, "/statics", latched())
        pub.publish(String("world -> odom"))
        first.shutdown()
        with Context("zenoh", domain_id=domain) as sub_ctx:
            got: list[str] = []
            sub_ctx.create_node("late").create_subscription(
                String, "/statics", lambda m: got.append(m.data), latched(depth=100)
            )
            deadline = time.monotonic() + scaled(20)
            while not got and time.monotonic() < deadline:
                sub_ctx.spin_once(0.05)
            assert got == ["world -> odom"]


def test_echo_keeps_all_with_qos_history_keep_all_and_reports_what_depth_1_lost() -> None:
    """``topic echo`` with ros2 topic echo's QoS options: two echoes whose output nobody reads
    while 400 messages of 1 KB arrive (their pipes fill, so they stop printing): with
    ``--qos-history keep_all`` every message is printed once read, in order; with
    ``--qos-depth 1`` the oldest waiting ones were dropped, and the echo reports them as
    ros2 topic echo reports a MESSAGE_LOST event."""
    from robomodel.runtime import Context
    from robomodel.runtime.msg import String
    from robomodel.runtime.qos import History, QoSProfile

    domain = _domain()
    common = ["topic", "echo", "/burst", "std_msgs/msg/String", "--domain-id", domain]
    keep_all = subprocess.Popen(
        [*ROBOMODEL, *common, "--qos-history", "keep_all", "--count", "400"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    depth_1 = subprocess.Popen(
        [*ROBOMODEL, *common, "--qos-depth", "1"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        with Context("zenoh", domain_id=int(domain)) as ctx:
            publisher = ctx.create_node("burst").create_publisher(
                String, "/burst", QoSProfile(10, history=History.KEEP_ALL)
            )
            wait_until(lambda: publisher.get_subscription_count() == 2, 30, what="two echoes")
            # the first message is read from the depth-1 echo before the burst: a gap is counted
            # from the last message an echo saw (rmw_zenoh's rule), so one that saw nothing
            # before the burst's end (a starved process) would print 400 and report nothing
            publisher.publish(String("001 " + "x" * 1000))
            assert depth_1.stdout is not None
            first = _lines_until(depth_1.stdout, "001 x", 60)
            assert "001 x" in "".join(first), first
            for i in range(2, 401):
                publisher.publish(String(f"{i:03d} " + "x" * 1000))
            ctx.spin(duration_s=0.2)  # the last messages leave before the session closes
        out, err = keep_all.communicate(timeout=scaled(60))
        assert keep_all.returncode == 0, err
        numbers = [int(doc.split()[1]) for doc in out.split("---\n") if doc.strip()]
        assert numbers == list(range(1, 401))
        assert "lost" not in out
        text = "".join(_lines_until(depth_1.stdout, "400 x", 60))
        assert "400 x" in text, text[-2000:]
        assert "A message was lost!!!\n\ttotal count change:" in text
        printed = [doc for doc in text.split("---\n") if doc.startswith("data: ")]
        assert len(printed) < 399
    finally:
        for proc in (keep_all, depth_1):
            proc.kill()
            proc.wait()
