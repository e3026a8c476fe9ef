"""The launch reference's node tables (docs/reference/launch.md) name every node robomodel's
launch maps (and no other)."""

from __future__ import annotations

import re

from robomodel.launch.nodes import supported
from tests.conftest import ROOT


def _listed(section: str) -> set[tuple[str, str]]:
    listed: set[tuple[str, str]] = set()
    for row in re.findall(r"^\| `([^|]+)` \| ([^|]+) \|", section, flags=re.M):
        packages = re.findall(r"`([^`]+)`", "`" + row[0] + "`")
        types = re.findall(r"`([^`]+)`", row[1])
        for package in packages:
            for kind in types or ["same"]:
                listed.add((package, package if kind == "same" else kind))
    return listed


def test_readme_node_tables_match_the_registry() -> None:
    section = (ROOT / "docs/reference/launch.md").read_text()
    ros1, ros2 = section.split("\n## ROS 2 launch files", 1)
    for dialect, part in (
        ("ros1", ros1),
        ("ros2", ros2.split("### The ROS 2 launch language")[0]),
    ):
        registered = {(package, executable) for package, executable, _ in supported(dialect)}
        assert registered == _listed(part), dialect
