"""robomodel's ROS 1 master against a real roscore, driven by Debian's ROS 1 tools.

The same sequence of tool runs goes to a real ``roscore`` and to ``robomodel master``; after
each step ``rosnode list``, ``rostopic list`` and ``rosservice list`` must agree, roscore's
``/rosout`` node (``/rosout``, ``/rosout_agg``, its logger services) included: ``robomodel
master`` runs one too. Anonymous node names (``/rostopic_PID_TIME``) are compared without their
numbers.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import textwrap
import xmlrpc.client
from pathlib import Path

import pytest

from tests.ros1wire.conftest import Ros1, free_port
from tests.timing import scaled, wait_until

# what roscore's /rosout node alone puts on the graph
ROSOUT = {
    "rosnode": ["/rosout"],
    "rostopic": ["/rosout", "/rosout_agg"],
    "rosservice": ["/rosout/get_loggers", "/rosout/set_logger_level"],
}
ANONYMOUS = re.compile(r"_\d+_\d+(?=/|$)")

# A Debian rospy node offering /trigger (std_srvs/Trigger) that ends after its first call, as
# rospy nodes end: unregistering everything with the master.
PROVIDER = textwrap.dedent(
    """
    import rospy
    from std_srvs.srv import Trigger, TriggerResponse

    def handle(request):
        rospy.Timer(rospy.Duration(0.2), lambda event: rospy.signal_shutdown("done"), True)
        return TriggerResponse(True, "ok")

    rospy.init_node("provider")
    rospy.Service("/trigger", Trigger, handle)
    rospy.spin()
    """
)


# ``rosnode list``, ``rostopic list`` and ``rosservice list`` as /usr/bin/rosnode, rostopic and
# rosservice run them (``import rosnode; rosnode.rosnodemain()``), the command line given as
# sys.argv and as the argument (rosservicemain's default is sys.argv at its import), in one
# start of Debian's Python: each tool's own start costs about a second of CPU.
# Prints one JSON object: tool -> [exit code, stdout, stderr].
_LISTS = r"""
import contextlib, io, json, sys
import rosnode, rostopic, rosservice
out = {}
for tool, main in (("rosnode", rosnode.rosnodemain), ("rostopic", rostopic.rostopicmain),
                   ("rosservice", rosservice.rosservicemain)):
    sys.argv = [tool, "list"]
    stdout, stderr = io.StringIO(), io.StringIO()
    code = 0
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        try:
            main(sys.argv)
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
    out[tool] = [code, stdout.getvalue(), stderr.getvalue()]
print(json.dumps(out))
"""


def _graph(ros1: Ros1) -> dict[str, list[str]]:
    run = ros1.run("/usr/bin/python3", "-c", _LISTS)
    assert run.returncode == 0, run.stderr
    out = {}
    for tool, (code, stdout, stderr) in json.loads(run.stdout).items():
        assert code == 0, (tool, stderr)
        out[tool] = sorted(ANONYMOUS.sub("_*", n) for n in stdout.split())
    return out


def _publishers_and_subscribers(ros1: Ros1, topic: str) -> tuple[int, int]:
    pubs, subs, _ = xmlrpc.client.ServerProxy(ros1.uri).getSystemState("/test")[2]
    return (
        sum(len(nodes) for name, nodes in pubs if name == topic),
        sum(len(nodes) for name, nodes in subs if name == topic),
    )


def _sequence(ros1: Ros1, tmp_path: Path) -> list[dict[str, list[str]]]:
    """The tool runs, and the graph after each step."""
    seen = []
    pub = ros1.run("/usr/bin/rostopic", "pub", "-1", "/foo", "std_msgs/String", "data: x")
    assert pub.returncode == 0, pub.stderr
    info = ros1.run("/usr/bin/rostopic", "info", "/foo")
    seen.append({**_graph(ros1), "info /foo": [str(info.returncode), info.stdout + info.stderr]})

    tmp_path.mkdir(parents=True, exist_ok=True)
    script = tmp_path / "provider.py"
    script.write_text(PROVIDER)
    provider = ros1.start(["/usr/bin/python3", str(script)])
    ros1.until(lambda: "/trigger" in ros1.names("services"), "/trigger")
    seen.append(_graph(ros1))
    call = ros1.run("/usr/bin/rosservice", "call", "/trigger")
    assert call.returncode == 0 and "ok" in call.stdout, call.stderr
    provider.wait(scaled(30))
    seen.append(_graph(ros1))

    assert ros1.run("/usr/bin/rosparam", "set", "/gain", "5").returncode == 0
    assert ros1.run("/usr/bin/rosparam", "get", "/gain").stdout.strip() == "5"
    assert ros1.run("/usr/bin/rosparam", "delete", "/gain").returncode == 0

    echo = ros1.start(["/usr/bin/rostopic", "echo", "/bar"])
    killed = ros1.start(
        ["/usr/bin/rostopic", "pub", "-r", "2", "/bar", "std_msgs/String", "data: y"]
    )
    ros1.until(lambda: _publishers_and_subscribers(ros1, "/bar") == (1, 1), "/bar's two ends")
    seen.append(_graph(ros1))
    killed.kill()  # SIGKILL: no unregistering; the master keeps it until `rosnode cleanup`
    killed.wait(scaled(30))
    ros1.stop(echo)  # SIGINT: rospy unregisters
    seen.append(_graph(ros1))
    cleanup = subprocess.run(
        ["/usr/bin/rosnode", "cleanup"],
        input="y\n",
        capture_output=True,
        text=True,
        env=ros1.env,
        timeout=scaled(60),
    )
    assert cleanup.returncode == 0, cleanup.stderr
    seen.append(_graph(ros1))
    return seen


def test_debian_tools_leave_the_same_graph_on_robomodel_s_master_as_on_roscore(
    ros1: Ros1, tmp_path: Path
) -> None:
    ros1.roscore()
    theirs = _sequence(ros1, tmp_path / "roscore")
    ros1.close()
    ours_graph = Ros1(tmp_path / "ours")
    try:
        master = ours_graph.robomodel("master", "-p", str(ours_graph.port))
        ours_graph.wait_for_master("robomodel master")
        ours = _sequence(ours_graph, tmp_path / "ours")
        assert master.poll() is None
    finally:
        ours_graph.close()
    assert ours == theirs
    after_pub, with_provider, after_call, with_killed, after_kill, after_cleanup = ours
    assert after_pub["info /foo"] == ["1", "ERROR: Unknown topic /foo\n"]
    assert {tool: after_pub[tool] for tool in ROSOUT} == ROSOUT
    assert "/trigger" in with_provider["rosservice"]
    assert after_call["rosservice"] == ROSOUT["rosservice"]
    assert "/bar" in with_killed["rostopic"]
    assert with_killed["rosnode"] == ["/rosout", "/rostopic_*", "/rostopic_*"]
    assert after_kill["rosnode"] == ["/rosout", "/rostopic_*"]  # the killed one stays
    assert after_cleanup == ROSOUT


def test_a_garbage_registration_leaves_rospy_subscribers_receiving(
    ros1: Ros1, tmp_path: Path
) -> None:
    """Finding 1 with a launch-hosted master and Debian's rospy: a subscriber started first
    still receives once a publisher starts after the attack (the master's publisherUpdate
    reaches it)."""
    log = tmp_path / "launch.log"
    launch = ros1.robomodel(
        "launch", "gripper_description", "display.launch", "--headless", "--ros1-master", ros1.uri,
        log=log,
    )  # fmt: skip
    ros1.until(lambda: "nodes running" in log.read_text() or launch.poll() is not None, "launch")
    echo_log = tmp_path / "echo.log"
    ros1.start(["/usr/bin/rostopic", "echo", "/t"], log=echo_log)
    # rostopic echo subscribes once /t has a publisher of a type: its node is on the graph
    ros1.until(
        lambda: any(n.startswith("/rostopic_") for n in ros1.names("nodes")), "rostopic echo"
    )
    master = xmlrpc.client.ServerProxy(ros1.uri)
    for api in ("garbage", "rosrpc://127.0.0.1:1"):
        master.registerSubscriber("/evil", "/t", "std_msgs/String", api)
    master.registerPublisher("/evil", "/t", "std_msgs/String", "http://127.0.0.1:9/")
    ros1.start(["/usr/bin/rostopic", "pub", "-r", "5", "/t", "std_msgs/String", "data: after"])
    ros1.until(lambda: 'data: "after"' in echo_log.read_text(), "a message after the attack")
    assert launch.poll() is None
    assert "Traceback" not in log.read_text()


@pytest.mark.parametrize(
    ("variable", "host"),
    [("ROS_IP", "127.0.0.2"), ("ROS_IP", "::1"), ("ROS_HOSTNAME", "ip6-localhost")],
)
def test_loopback_addresses_bind_loopback_only(
    variable: str, host: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    from robomodel.runtime.transport.ros1.names import bind_host, listen_host, master_bind_host

    monkeypatch.delenv("ROS_IP", raising=False)
    monkeypatch.delenv("ROS_HOSTNAME", raising=False)
    monkeypatch.setenv(variable, host)
    assert bind_host() == {"127.0.0.2": "127.0.0.2"}.get(host, "::1")
    assert listen_host("10.1.2.3") == "0.0.0.0" and listen_host("2001:db8::1") == "::"
    # the master listens where ROS_MASTER_URI points, loopback only for a loopback URI
    assert master_bind_host("http://localhost:11311/") == "127.0.0.1"
    assert master_bind_host("http://[::1]:11311/") == "::1"
    monkeypatch.setenv("ROS_IP", "10.1.2.3")  # an address others use: every interface
    assert master_bind_host("http://localhost:11311/") == "0.0.0.0"


def test_robomodel_master_and_nodes_on_ipv6_loopback(tmp_path: Path) -> None:
    """``ROS_IP=::1``: ``robomodel master -p`` starts (it did not), listens on ::1 only, and
    robomodel's nodes talk over it (node XML-RPC and TCPROS on ::1; Debian's rospy would need
    ROS_IPV6=on)."""
    port = free_port()
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS")}
    env.update(ROS_IP="::1", ROS_MASTER_URI=f"http://[::1]:{port}/")
    err = tmp_path / "master.err"
    from tests.conftest import ROBOMODEL

    with err.open("w") as stderr:
        master = subprocess.Popen([*ROBOMODEL, "master", "-p", str(port)], stderr=stderr, env=env)
    try:
        wait_until(
            lambda: "started ROS 1 master at http://[::1]:" in err.read_text() or _ended(master),
            60,
            what="the master to start",
            interval_s=0.1,
        )
        pub = subprocess.Popen(
            [*ROBOMODEL, "topic", "pub", "/six", "std_msgs/msg/String", "{data: six}", "-r", "5"],
            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        )  # fmt: skip
        try:
            echo = subprocess.run(
                [*ROBOMODEL, "topic", "echo", "/six", "--once"],
                env=env, capture_output=True, text=True, timeout=scaled(120),
            )  # fmt: skip
        finally:
            pub.terminate()
            pub.wait(scaled(30))
        assert echo.returncode == 0 and "six" in echo.stdout, echo.stderr
        import socket

        with pytest.raises(OSError):  # loopback ::1 only: not IPv4, not other interfaces
            # refused at once; a timeout would be an OSError too, so its length is not scaled
            socket.create_connection(("127.0.0.1", port), timeout=5).close()
    finally:
        master.terminate()
        master.wait(scaled(30))
    assert "Traceback" not in err.read_text()


def _ended(proc: subprocess.Popen[bytes]) -> bool:
    """Never true: fails at once when ``proc`` has ended (a wait for it would be in vain)."""
    assert proc.poll() is None, "the master did not start"
    return False
