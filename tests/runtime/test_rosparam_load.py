"""``param load`` of a multi-document YAML file: each document's ``_ns`` key names where it goes
and is not itself a parameter, as rosparam's ``load_str`` does."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path
from typing import Any

import pytest

from robomodel.cli._rosparam import load_documents
from tests.timing import scaled

DOCUMENTS = "_ns: arm\ngain: 2\n---\n_ns: /abs\nk: 1\n---\nplain: 3\n"
EXPECTED = [({"gain": 2}, "/robot/arm"), ({"k": 1}, "/abs"), ({"plain": 3}, "/robot")]


def _debian_rosparam(text: str, namespace: str) -> list[tuple[Any, str]] | None:
    """rosparam.load_str of ``text`` by Debian's ROS 1 Python, or None where it is missing."""
    python = shutil.which("python3", path="/usr/bin")
    if python is None:
        return None
    code = (
        "import json, sys, rosparam; "
        "print(json.dumps(rosparam.load_str(sys.stdin.read(), 'f', default_namespace=sys.argv[1])))"
    )
    done = subprocess.run(
        [python, "-c", code, namespace], input=text, capture_output=True, text=True,
        timeout=scaled(30), check=False,
    )  # fmt: skip
    if done.returncode != 0:
        return None
    return [(values, ns) for values, ns in json.loads(done.stdout)]


def test_ns_keys_place_documents_and_are_not_parameters(tmp_path: Path) -> None:
    path = tmp_path / "params.yaml"
    path.write_text(DOCUMENTS)
    assert load_documents(str(path), "/robot") == EXPECTED


def test_ns_handling_equals_debian_s_rosparam(tmp_path: Path) -> None:
    reference = _debian_rosparam(DOCUMENTS, "/robot")
    if reference is None:
        pytest.skip("Debian's ROS 1 rosparam Python package is not installed")
    path = tmp_path / "params.yaml"
    path.write_text(DOCUMENTS)
    assert reference == EXPECTED  # so that a reference that changed cannot pass unnoticed
    assert load_documents(str(path), "/robot") == reference
