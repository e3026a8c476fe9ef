"""``robomodel log`` on the Zenoh bus: robomodel nodes' /rosout lines in rqt_console's columns,
filtered by node glob and minimum severity, peers' text escaped. The ROS 1 side (Debian's
rospy as the node) is ``tests/ros1wire/test_log_ros1.py``."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

from robomodel.cli.log import LogLine, format_line, matches
from tests.conftest import ROBOMODEL, ROOT, unique_domain
from tests.timing import scaled

CHATTY = """
import logging, sys, time
from robomodel.runtime import Context

with Context("zenoh", domain_id=int(sys.argv[1])) as ctx:
    arm = ctx.create_node("talker", "/arm")
    base = ctx.create_node("talker", "/base")
    for node in (arm, base):
        node.logger.setLevel(logging.DEBUG)  # every level goes to /rosout
    print("ready", flush=True)
    k = 0
    while True:  # until the test kills it
        arm.logger.debug("arm debug %d", k)
        arm.logger.info("arm info %d", k)
        arm.logger.warning("arm warning %d\\x1b]0;retitled\\x07", k)
        arm.logger.error("arm error %d\\nsecond line", k)
        base.logger.error("base error %d", k)
        k += 1
        ctx.spin(duration_s=0.2)
"""


def test_log_shows_matching_nodes_at_or_above_the_level(tmp_path: Path) -> None:
    domain = unique_domain()
    script = tmp_path / "chatty.py"
    script.write_text(CHATTY)
    env = {**os.environ, "PYTHONPATH": f"{ROOT / 'src'}:{ROOT}"}
    chatty = subprocess.Popen(
        [sys.executable, str(script), domain], stdout=subprocess.PIPE, text=True, env=env
    )
    try:
        assert chatty.stdout is not None and chatty.stdout.readline().strip() == "ready"
        done = subprocess.run(
            [*ROBOMODEL, "log", "--node", "/arm/*", "--level", "warn", "-n", "6",
             "--domain-id", domain],
            capture_output=True, text=True, timeout=scaled(60),
        )  # fmt: skip
    finally:
        chatty.send_signal(signal.SIGKILL)
        chatty.wait()
    assert done.returncode == 0, done.stderr
    assert done.stderr.splitlines()[0].startswith("robomodel log: bus: zenoh (rmw_zenoh), domain")
    lines = done.stdout.splitlines()
    assert len(lines) == 6
    severities = {line.split()[1] for line in lines}
    assert severities == {"WARN", "ERROR"}  # no DEBUG or INFO: below --level warn
    assert all(line.split()[2] == "/arm/talker" for line in lines)  # not /base/talker
    warning = next(line for line in lines if " WARN " in line)
    assert "\x1b" not in done.stdout and "\\x1b]0;retitled\\x07" in warning
    error = next(line for line in lines if " ERROR " in line)
    assert "arm error" in error and "\\x0asecond line" in error  # one line per record
    assert "chatty.py:" in warning.rsplit("  ", 1)[-1]  # file:line of the logging call
    stamp = float(lines[0].split()[0])
    assert stamp > 1.6e9  # seconds since 1970 (the wall clock), with nanoseconds


def test_log_ends_cleanly_on_sigterm() -> None:
    domain = unique_domain()
    proc = subprocess.Popen(
        [*ROBOMODEL, "log", "--domain-id", domain], stderr=subprocess.PIPE, text=True
    )
    assert proc.stderr is not None
    assert proc.stderr.readline().startswith("robomodel log: bus: zenoh")
    proc.send_signal(signal.SIGTERM)
    assert proc.wait(scaled(30)) == 0
    assert "Traceback" not in proc.stderr.read()


def test_filters_and_columns() -> None:
    line = LogLine(1_700_000_000_000_000_042, "info", "ns.talker", "hi", "/a/b.py", 7)
    assert format_line(line) == "1700000000.000000042  INFO   ns.talker  hi  /a/b.py:7"
    assert matches(line, ["/ns/*"], "info") and matches(line, ["ns.*"], "debug")
    assert not matches(line, ["/other*"], "debug") and not matches(line, [], "warn")
    odd = LogLine(0, "7", "/x", "m", "", 0)  # a level no ROS defines is shown, not filtered
    assert matches(odd, [], "fatal") and format_line(odd).split()[1] == "7"


def test_a_flood_of_huge_lines_prints_each_cut_to_its_bound() -> None:
    """A peer's megabyte message, or a megabyte node name, is printed cut, saying how long it
    was; the node column of later lines stays narrow."""
    from robomodel.cli.log import MAX_MESSAGE_CHARS, MAX_NAME_CHARS, MAX_NODE_COLUMN

    huge = LogLine(0, "info", "n" * 10**6, "\x1b" + "m" * 10**6, "f" * 10**6, 1)
    text = format_line(huge, node_width=10**6)
    assert len(text) < 4 * MAX_MESSAGE_CHARS + MAX_NAME_CHARS + 200
    assert "… (1000001 characters)" in text and text.count("… (1000000 characters)") == 2
    assert "\\x1b" in text and "\x1b" not in text
    short = format_line(LogLine(0, "info", "talker", "hi", "", 0), node_width=10**6)
    assert short == f"0.000000000  INFO   {'talker'.ljust(MAX_NODE_COLUMN)}  hi"
