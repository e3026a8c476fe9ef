"""``robomodel log`` on ROS 1: a Debian rospy node's /rosout lines (rosgraph_msgs/Log) beside
Debian's roscore, in rqt_console's columns, filtered by node and severity, text escaped."""

from __future__ import annotations

from pathlib import Path

from tests.conftest import ROBOMODEL
from tests.ros1wire.conftest import Ros1
from tests.timing import scaled

CHATTY = """
import rospy

rospy.init_node("chatty")
rate = rospy.Rate(5)
k = 0
while not rospy.is_shutdown():  # until the test ends it
    rospy.loginfo("info %d", k)
    rospy.logwarn("warning %d \\x1b[31mred", k)
    rospy.logerr("error %d", k)
    k += 1
    rate.sleep()
"""


def test_log_shows_a_rospy_node_s_rosout_lines(ros1: Ros1, tmp_path: Path) -> None:
    ros1.roscore()
    script = tmp_path / "chatty.py"
    script.write_text(CHATTY)
    ros1.start(["/usr/bin/python3", str(script)])
    quiet = ros1.start(["/usr/bin/rostopic", "pub", "-r", "5", "/rosout", "rosgraph_msgs/Log",
                        "{level: 8, name: /quiet, msg: from rostopic}"])  # fmt: skip
    done = ros1.run(
        *ROBOMODEL, "log", "--node", "/chat*", "--level", "warn", "-n", "4",
        timeout=scaled(60),
    )  # fmt: skip
    alone = ros1.run(*ROBOMODEL, "log", "--node", "/quiet", "-n", "1", timeout=scaled(60))
    ros1.stop(quiet)
    assert alone.returncode == 0, alone.stderr
    assert alone.stdout.split()[1:] == ["ERROR", "/quiet", "from", "rostopic"]  # no file given
    assert done.returncode == 0, done.stderr
    assert done.stderr.splitlines()[0].startswith(f"robomodel log: bus: ros1, master {ros1.uri}")
    lines = done.stdout.splitlines()
    assert len(lines) == 4
    assert {line.split()[1] for line in lines} == {"WARN", "ERROR"}  # rospy's 4 and 8
    assert {line.split()[2] for line in lines} == {"/chatty"}  # not /quiet
    warning = next(line for line in lines if " WARN " in line)
    assert "\x1b" not in done.stdout and "\\x1b[31mred" in warning
    assert warning.endswith(tuple(f"chatty.py:{n}" for n in range(1, 20)))  # rospy's file:line
