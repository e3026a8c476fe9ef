"""The README's node table names every node robomodel's launch maps (and no other)."""

from __future__ import annotations

import re

from robomodel.launch.nodes import supported
from tests.conftest import ROOT


def test_readme_node_table_matches_the_registry() -> None:
    text = (ROOT / "README.md").read_text()
    section = text.split("## Launch files: `robomodel launch`", 1)[1].split("\n## ", 1)[0]
    listed: set[tuple[str, str]] = set()
    for row in re.findall(r"^\| `([^|]+)` \| ([^|]+) \|", section, flags=re.M):
        packages = re.findall(r"`([^`]+)`", "`" + row[0] + "`")
        types = re.findall(r"`([^`]+)`", row[1])
        for package in packages:
            for kind in types or ["same"]:
                listed.add((package, package if kind == "same" else kind))
    registered = {(package, executable) for package, executable, _ in supported("ros1")}
    assert registered == listed
