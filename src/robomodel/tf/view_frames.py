"""view_frames' Graphviz text from a buffer: tf2_tools' (``view_frames.py generate_dot``) and ROS 1
tf's (``allFramesAsDot``, tf2's ``BufferCore::_allFramesAsDot``).

Frame and broadcaster names come from peers, so each is written as a DOT quoted string
(:func:`dot_quoted`): a name holding ``"`` cannot end its ID and start an edge of its own.
"""

from __future__ import annotations

from typing import Any

from robomodel._yaml_bounded import load_yaml_data
from robomodel.tf.buffer import BufferCore

__all__ = ["dot_quoted", "frames_dot", "tf_frames_dot"]


def _dot_char(char: str) -> str:
    if char == "\\":
        return "\\\\"
    if char == '"':
        return '\\"'
    if char.isprintable():
        return char
    return f"\\\\x{ord(char):02x}"  # shown as \x0a: a name's line break is not the label's


def dot_escaped(text: str) -> str:
    """``text`` for inside a DOT quoted string: Graphviz's only escape there is ``\\"``, so a
    backslash is doubled too (a trailing one would escape the closing quote; in a label
    ``\\\\`` shows one backslash), and characters that are not printable are spelt out."""
    if text.isprintable() and '"' not in text and "\\" not in text:
        return text
    return "".join(_dot_char(char) for char in text)


def dot_quoted(text: str) -> str:
    """``text`` as a DOT ID: a quoted string (Graphviz's lang.html, "ID")."""
    return f'"{dot_escaped(text)}"'


def _frames(buffer: BufferCore) -> Any:
    return load_yaml_data(buffer.all_frames_as_yaml(), what="the tf frames")


def frames_dot(buffer: BufferCore, *, recorded_time_s: float = 0.0) -> str:
    """The dot text view_frames writes, from ``buffer.all_frames_as_yaml()``.

    Values go through a YAML round trip exactly as view_frames does (so ``10000.000`` becomes
    ``10000.0``).
    """
    data: Any = _frames(buffer)
    if not data:
        return 'digraph G { "No tf data received" }'
    dot = "digraph G {\n"
    root = ""
    for frame, info in data.items():
        dot += f"{dot_quoted(str(info['parent']))} -> {dot_quoted(str(frame))}"
        dot += '[label=" '
        dot += f"Broadcaster: {dot_escaped(str(info['broadcaster']))}\\n"
        dot += f"Average rate: {info['rate']}\\n"
        dot += f"Buffer length: {info['buffer_length']}\\n"
        dot += f"Most recent transform: {info['most_recent_transform']}\\n"
        dot += f"Oldest transform: {info['oldest_transform']}\\n"
        dot += '"];\n'
        if info["parent"] not in data:
            root = info["parent"]
    dot += "edge [style=invis];\n"
    dot += ' subgraph cluster_legend { style=bold; color=black; label ="view_frames Result";\n'
    dot += f'"Recorded at time: {recorded_time_s}"[ shape=plaintext ] ;\n'
    dot += f"}}->{dot_quoted(str(root))};\n}}"
    return dot


def tf_frames_dot(buffer: BufferCore, *, current_time_s: float) -> str:
    """ROS 1 tf's ``allFramesAsDot(now)``, what ``rosrun tf view_frames`` writes to frames.gv.

    Transcribed from tf2's ``BufferCore::_allFramesAsDot(double current_time)``: one edge per
    frame with a parent (frames in the order tf2 numbers them, a child before its parent),
    values with 3 decimals, then the legend pointing at each frame that is only a parent.
    """
    data: Any = _frames(buffer) or {}
    dot = "digraph G {\n"
    if not buffer.frames:
        dot += '"no tf data recieved"'  # tf2's spelling
    for frame, info in data.items():
        latest_s = float(info["most_recent_transform"])
        dot += (
            f"{dot_quoted(str(info['parent']))} -> {dot_quoted(str(frame))}"
            f'[label="Broadcaster: {dot_escaped(str(info["broadcaster"]))}\\n'
            f"Average rate: {float(info['rate']):.3f} Hz\\n"
            f"Most recent transform: {latest_s:.3f} ( {current_time_s - latest_s:.3f} sec old)"
            f'\\nBuffer length: {float(info["buffer_length"]):.3f} sec\\n"];\n'
        )
    for root in (f for f in buffer.frames if f not in data):
        dot += "edge [style=invis];\n"
        dot += ' subgraph cluster_legend { style=bold; color=black; label ="view_frames Result";\n'
        dot += f'"Recorded at time: {current_time_s:.3f}"[ shape=plaintext ] ;\n }}->'
        dot += f"{dot_quoted(root)};\n"
    return dot + "}"
