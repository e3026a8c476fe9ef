"""A ROS 2 node's parameters from its launch sources, as rcl resolves them.

A launch ``Node`` gets ``parameters=[...]``: dicts (nested dicts are dotted names, as
launch_ros flattens them) and YAML parameter files, read by
:func:`~robomodel.runtime.param_files.parameters_from_file` (rcl's node-name matching).
Later sources override earlier ones.
"""

from __future__ import annotations

from typing import Any

from robomodel.launch.model import NodeSpec
from robomodel.runtime.param_files import flatten, parameters_from_file

__all__ = ["node_parameters"]


def node_parameters(spec: NodeSpec, *, name: str | None = None) -> dict[str, Any]:
    """Every parameter of ``spec`` in order (``name``: the node's name when the launch file
    gave none, the executable's default)."""
    fqn = spec.namespace.rstrip("/") + "/" + (spec.name or name or spec.executable)
    out: dict[str, Any] = {}
    for source in spec.parameters:
        if source.values is not None:
            out.update(flatten(source.values))
        elif source.file is not None:
            out.update(parameters_from_file(source.file, fqn))
    return out
