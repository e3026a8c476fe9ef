"""view_frames' Graphviz text from a buffer: tf2_tools' (``view_frames.py generate_dot``) and ROS 1
tf's (``allFramesAsDot``, tf2's ``BufferCore::_allFramesAsDot``)."""

from __future__ import annotations

from typing import Any

import yaml

from robomodel.tf.buffer import BufferCore

__all__ = ["frames_dot", "tf_frames_dot"]


def frames_dot(buffer: BufferCore, *, recorded_time_s: float = 0.0) -> str:
    """The dot text view_frames writes, from ``buffer.all_frames_as_yaml()``.

    Values go through a YAML round trip exactly as view_frames does (so ``10000.000`` becomes
    ``10000.0``).
    """
    data: Any = yaml.safe_load(buffer.all_frames_as_yaml())
    if not data:
        return 'digraph G { "No tf data received" }'
    dot = "digraph G {\n"
    root = ""
    for frame, info in data.items():
        dot += f'"{info["parent"]}" -> "{frame}"'
        dot += '[label=" '
        dot += f"Broadcaster: {info['broadcaster']}\\n"
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
    dot += f'}}->"{root}";\n}}'
    return dot


def tf_frames_dot(buffer: BufferCore, *, current_time_s: float) -> str:
    """ROS 1 tf's ``allFramesAsDot(now)``, what ``rosrun tf view_frames`` writes to frames.gv.

    Transcribed from tf2's ``BufferCore::_allFramesAsDot(double current_time)``: one edge per
    frame with a parent (frames in the order tf2 numbers them, a child before its parent),
    values with 3 decimals, then the legend pointing at each frame that is only a parent.
    """
    data: Any = yaml.safe_load(buffer.all_frames_as_yaml()) or {}
    dot = "digraph G {\n"
    if not buffer.frames:
        dot += '"no tf data recieved"'  # tf2's spelling
    for frame, info in data.items():
        latest_s = float(info["most_recent_transform"])
        dot += (
            f'"{info["parent"]}" -> "{frame}"[label="Broadcaster: {info["broadcaster"]}\\n'
            f"Average rate: {float(info['rate']):.3f} Hz\\n"
            f"Most recent transform: {latest_s:.3f} ( {current_time_s - latest_s:.3f} sec old)"
            f'\\nBuffer length: {float(info["buffer_length"]):.3f} sec\\n"];\n'
        )
    for root in (f for f in buffer.frames if f not in data):
        dot += "edge [style=invis];\n"
        dot += ' subgraph cluster_legend { style=bold; color=black; label ="view_frames Result";\n'
        dot += f'"Recorded at time: {current_time_s:.3f}"[ shape=plaintext ] ;\n }}->"{root}";\n'
    return dot + "}"
