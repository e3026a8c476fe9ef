"""What a ROS 1 launch file describes, once loaded (roslaunch's ROSLaunchConfig, frozen)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from robomodel.errors import SourceLocation
from robomodel.launch.model import NodeSpec

__all__ = ["MachineSpec", "ParamDump", "Ros1Launch"]


@dataclass(frozen=True, slots=True)
class MachineSpec:
    """A ``<machine>`` (parsed; robomodel runs every node locally)."""

    name: str
    address: str
    location: SourceLocation | None = None


@dataclass(frozen=True, slots=True)
class ParamDump:
    """``<rosparam command="dump" file=... param=...>``, run when the launch starts."""

    file: str
    param: str


@dataclass(frozen=True, slots=True)
class Ros1Launch:
    """A loaded ROS 1 launch file and everything it includes.

    Attributes:
        path: The top-level file.
        params: Global parameter name -> value, in the order the launch sets them (later
            settings of the same name win, as on the parameter server).
        nodes: The ``<node>`` tags, in launch order (dialect ``ros1``).
        tests: The ``<test>`` tags (parsed, never run).
        clear_params: Namespaces cleared before the parameters are set.
        param_deletes: ``<rosparam command="delete">`` names, applied before setting.
        param_dumps: ``<rosparam command="dump">`` requests.
        machines: ``<machine>`` tags.
        files: Every launch file loaded (top-level first).
        arg_docs: The top-level file's args as ``--ros-args`` lists them: name -> (doc, default).
        declared_args: The names of every ``<arg>`` of every file loaded, in order.
        warnings: What roslaunch reports as configuration errors (unknown attributes, ...).
    """

    path: Path
    params: Mapping[str, Any] = field(default_factory=dict)
    nodes: tuple[NodeSpec, ...] = ()
    tests: tuple[NodeSpec, ...] = ()
    clear_params: tuple[str, ...] = ()
    param_deletes: tuple[str, ...] = ()
    param_dumps: tuple[ParamDump, ...] = ()
    machines: tuple[MachineSpec, ...] = ()
    files: tuple[Path, ...] = ()
    arg_docs: Mapping[str, tuple[str | None, str | None]] = field(default_factory=dict)
    declared_args: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()

    def node(self, fqn: str) -> NodeSpec:
        """The node (or test) whose fully qualified name is ``fqn``."""
        for spec in (*self.nodes, *self.tests):
            if spec.fqn == fqn:
                return spec
        raise KeyError(fqn)
