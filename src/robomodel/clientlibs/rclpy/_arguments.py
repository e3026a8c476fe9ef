"""ROS 2's command-line arguments, as rcl parses them (``rcl_parse_arguments``).

``--ros-args`` opens a section and ``--`` (or the end) closes it. In a section:
``-r``/``--remap [node:]from:=to`` (``__ns:=`` and ``__node:=`` rename), ``-p``/``--param
[node:]name:=value`` (a YAML value), ``--params-file FILE``, ``--log-level [name:=]LEVEL``,
``--enable-rosout-logs``/``--disable-rosout-logs``, ``--enable-stdout-logs``/
``--disable-stdout-logs``, ``--enable-external-lib-logs``/``--disable-external-lib-logs``,
``-e``/``--enclave`` (accepted; robomodel has no security enclaves).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from robomodel.errors import RobomodelError

__all__ = ["RosArguments", "RosArgumentsError", "parse_ros_arguments", "remove_ros_args"]

_ROS_ARGS = "--ros-args"
_FLAGS = {"--enable-rosout-logs", "--disable-rosout-logs", "--enable-stdout-logs",
          "--disable-stdout-logs", "--enable-external-lib-logs", "--disable-external-lib-logs"}  # fmt: skip
_WITH_VALUE = {"-r", "--remap", "-p", "--param", "--params-file", "--log-level", "-e", "--enclave",
               "--log-file-name", "--log-config-file"}  # fmt: skip


class RosArgumentsError(RobomodelError, ValueError):
    """A ``--ros-args`` section rcl would refuse."""


@dataclass
class RosArguments:
    """What the ``--ros-args`` sections of one argument list say."""

    remaps: list[tuple[str | None, str, str]] = field(default_factory=list)  # (node, from, to)
    # (node, name, value) of -p, or a --params-file's Path, in the order given: later wins
    params: list[tuple[str | None, str, Any] | Path] = field(default_factory=list)
    log_levels: list[tuple[str | None, str]] = field(default_factory=list)  # (logger, level)
    rosout: bool = True
    stdout: bool = True

    def node_name(self, name: str) -> str:
        return self._special("__node", name) or name

    def namespace(self, namespace: str | None, name: str) -> str | None:
        return self._special("__ns", name) or namespace

    def _special(self, key: str, name: str) -> str | None:
        found = None
        for node, source, target in self.remaps:
            if source == key and node in (None, name):
                found = target
        return found

    def remappings(self, name: str) -> dict[str, str]:
        """The topic and service remappings for node ``name`` (later rules win)."""
        out: dict[str, str] = {}
        for node, source, target in self.remaps:
            if not source.startswith("__") and node in (None, name):
                out[source] = target
        return out

    def overrides(self, fq_name: str) -> dict[str, Any]:
        """Parameter values for node ``fq_name`` from ``-p`` and ``--params-file``, a later
        one winning over an earlier one (rcl applies them in order)."""
        from robomodel.runtime.param_files import parameters_from_file

        out: dict[str, Any] = {}
        bare = fq_name.rsplit("/", 1)[-1]
        for entry in self.params:
            if isinstance(entry, Path):
                out.update(parameters_from_file(entry, fq_name))
                continue
            node, name, value = entry
            if node in (None, bare, fq_name, fq_name.lstrip("/")):
                out[name] = value
        return out


def _split_node(rule: str) -> tuple[str | None, str]:
    """``talker:chatter:=x`` -> (``talker``, ``chatter:=x``); a ``:`` before ``:=`` only."""
    head, sep, _ = rule.partition(":=")
    if sep and ":" in head:
        node, _, rest = rule.partition(":")
        return node, rest
    return None, rule


def _rule(option: str, text: str) -> tuple[str | None, str, str]:
    node, rest = _split_node(text)
    source, sep, target = rest.partition(":=")
    if not sep or not source or not target:
        wanted = "from:=to" if option in ("-r", "--remap") else "name:=value"
        raise RosArgumentsError(f"Couldn't parse {option} '{text}': expected {wanted}")
    return node, source, target


def parse_ros_arguments(args: Sequence[str]) -> RosArguments:
    """Parse the ``--ros-args`` sections of ``args`` (the rest is the program's)."""
    from robomodel.runtime.params import parse_parameter_value

    parsed = RosArguments()
    inside = False
    index = 0
    while index < len(args):
        arg = args[index]
        index += 1
        if arg == _ROS_ARGS:
            inside = True
            continue
        if not inside:
            continue
        if arg == "--":
            inside = False
            continue
        if arg in _FLAGS:
            enable = arg.startswith("--enable")
            if "rosout" in arg:
                parsed.rosout = enable
            elif "stdout" in arg:
                parsed.stdout = enable
            continue
        if arg not in _WITH_VALUE:
            raise RosArgumentsError(
                f"unknown ROS argument '{arg}' after --ros-args; expected one of: "
                f"{', '.join(sorted(_WITH_VALUE | _FLAGS))} (end the section with '--')"
            )
        if index >= len(args):
            raise RosArgumentsError(f"ROS argument '{arg}' needs a value")
        value = args[index]
        index += 1
        if arg in ("-r", "--remap"):
            parsed.remaps.append(_rule(arg, value))
        elif arg in ("-p", "--param"):
            node, name, text = _rule(arg, value)
            parsed.params.append((node, name, parse_parameter_value(text)))
        elif arg == "--params-file":
            parsed.params.append(Path(value))
        elif arg == "--log-level":
            logger, sep, level = value.rpartition(":=")
            parsed.log_levels.append((logger if sep else None, level))
    return parsed


def remove_ros_args(args: Sequence[str]) -> list[str]:
    """``args`` without its ``--ros-args`` sections (``argv[0]`` kept)."""
    out: list[str] = []
    inside = False
    index = 0
    while index < len(args):
        arg = args[index]
        index += 1
        if arg == _ROS_ARGS:
            inside = True
        elif inside and arg == "--":
            inside = False
        elif inside and arg in _WITH_VALUE:
            index += 1
        elif not inside:
            out.append(arg)
    return out
