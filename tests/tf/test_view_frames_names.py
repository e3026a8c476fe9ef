"""Frame and broadcaster names from peers reach view_frames' YAML and DOT as the names.

A ``/tf`` child frame is named by whoever publishes it: ``it's: [x`` written unquoted into
tf2's YAML ended view_frames in a ScannerError, and ``b" -> "PWNED" [label="injected`` written
into frames.gv unescaped added an edge of its own. Each name is now quoted for the format it
enters; Graphviz itself (``dot -Tjson``) reads back exactly the tree that was heard.
"""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import pytest
import yaml

from robomodel.tf import BufferCore
from robomodel.tf.message import TransformStamped
from robomodel.tf.view_frames import dot_quoted, frames_dot, tf_frames_dot

HOSTILE = (
    "it's: [x",
    'b" -> "PWNED" [label="injected',
    "line\nbreak",
    "trailing\\",
    "true",
    "- item",
    "#comment",
    "tab\there",
)
BROADCASTER = 'node" ];\n"x" -> "y'


def _buffer() -> BufferCore:
    buffer = BufferCore()
    for k, name in enumerate(HOSTILE):
        stamp = TransformStamped("world", name, (float(k), 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), 10**9)
        buffer.set_transform(stamp, BROADCASTER)
    return buffer


def test_tf2_yaml_reads_back_as_the_names_heard() -> None:
    data = yaml.safe_load(_buffer().all_frames_as_yaml())
    assert list(data) == list(HOSTILE)
    assert {info["parent"] for info in data.values()} == {"world"}
    assert {info["broadcaster"] for info in data.values()} == {BROADCASTER}


def test_ordinary_names_are_written_as_tf2_writes_them() -> None:
    buffer = BufferCore()
    buffer.set_transform(TransformStamped("base", "arm", (0.0, 0.0, 0.0), (0, 0, 0, 1), 0), "rsp")
    assert buffer.all_frames_as_yaml().startswith("arm: \n  parent: 'base'\n  broadcaster: 'rsp'\n")


def _graph(dot_text: str) -> tuple[set[str], list[tuple[str, str]], list[str]]:
    dot = shutil.which("dot")
    if dot is None:
        pytest.skip("Graphviz's dot is not installed (tools/system-deps test installs it)")
    done = subprocess.run([dot, "-Tjson"], input=dot_text, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    graph = json.loads(done.stdout)
    objects = graph.get("objects", [])
    names = {o["name"] for o in objects if "nodes" not in o}  # not the legend's cluster
    edges = [(objects[e["tail"]]["name"], objects[e["head"]]["name"]) for e in graph["edges"]]
    labels = [e.get("label", "") for e in graph["edges"]]
    return names, edges, labels


@pytest.mark.parametrize("write", [frames_dot, tf_frames_dot], ids=["tf2_tools", "tf"])
def test_graphviz_reads_the_tree_that_was_heard(write: object) -> None:
    text = (
        frames_dot(_buffer(), recorded_time_s=1.0)
        if write is frames_dot
        else tf_frames_dot(_buffer(), current_time_s=2.0)
    )
    names, edges, labels = _graph(text)
    heard = {name.replace("\\", "\\\\").replace("\n", "\\\\x0a").replace("\t", "\\\\x09") for name in HOSTILE}  # fmt: skip
    assert "PWNED" not in names and "y" not in names
    tree = [(tail, head) for tail, head in edges if not tail.startswith("Recorded at time")]
    assert sorted(tree) == sorted(("world", name) for name in heard)
    shown = BROADCASTER.replace("\n", "\\\\x0a")  # the label attribute as written
    assert all(f"Broadcaster: {shown}\\n" in label for label in labels[: len(HOSTILE)])


def test_a_dot_id_holds_any_text() -> None:
    assert dot_quoted("plain") == '"plain"'
    assert dot_quoted('a"b') == '"a\\"b"'
    assert dot_quoted("end\\") == '"end\\\\"'
    assert dot_quoted("a\nb") == '"a\\\\x0ab"'


def test_dot_runs_with_a_timeout_and_a_size_bound(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from robomodel.cli import graph
    from robomodel.errors import RobomodelError

    if shutil.which("dot") is None:
        pytest.skip("Graphviz's dot is not installed (tools/system-deps test installs it)")
    text = frames_dot(_buffer(), recorded_time_s=1.0)
    with pytest.raises(RobomodelError, match=r"^dot did not render '.*frames.pdf' within 0.001 s"):
        graph.render_dot(text, tmp_path / "frames.pdf", timeout_s=0.001)
    monkeypatch.setattr(graph, "MAX_DOT_BYTES", 1000)
    with pytest.raises(RobomodelError, match=r"bytes of Graphviz text, more than the 1000"):
        graph.render_dot(text, tmp_path / "frames.pdf")
    assert not list(tmp_path.iterdir())
