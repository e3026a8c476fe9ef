"""view_frames' Graphviz text (``tf2_tools/view_frames.py generate_dot``) from a buffer."""

from __future__ import annotations

from typing import Any

import yaml

from robomodel.tf.buffer import BufferCore

__all__ = ["frames_dot"]


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
