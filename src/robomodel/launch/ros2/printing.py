"""``ros2 launch --show-args`` and ``--print`` output.

``format_show_args`` transcribes ros2launch's ``print_arguments_of_launch_description``;
``format_print`` transcribes launch's ``LaunchIntrospector`` (top-level entities; event handlers
with their entities). Differences: object addresses are printed as ``0x0`` (they differ at every
run upstream), and entities show robomodel's class paths under the upstream module names.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from robomodel.launch.ros2.model import Ros2Launch
from robomodel.launch.ros2.shim.action import Action, object_text
from robomodel.launch.ros2.shim.events import (
    EmitEvent,
    ExecuteProcess,
    LogInfo,
    RegisterEventHandler,
)
from robomodel.launch.ros2.shim.ros import Node

__all__ = ["describe_entities", "format_print", "format_show_args", "object_text"]


def format_show_args(launch: Ros2Launch) -> str:
    """Exactly what ``ros2 launch --show-args`` prints (with a final newline)."""
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    any_conditional = False
    for argument in launch.arguments:
        msg = f"\n    '{argument.name}':"
        if argument.conditional:
            any_conditional = True
            msg += "*"
        msg += "\n        " + argument.description
        if argument.default_description is not None:
            msg += f"\n        (default: {argument.default_description})"
        lines.append(msg)
    if launch.arguments:
        if any_conditional:
            lines.append("\n* argument(s) which are only used if specific conditions occur")
    else:
        lines.append("\n  No arguments.")
    return "\n".join(lines) + "\n"


def _subs(subs: Iterable[Any]) -> str:
    return " + ".join(sub.describe() for sub in subs)


def _indent(lines: list[str]) -> list[str]:
    return ["    " + line for line in lines]


def describe_entities(entities: Iterable[Any]) -> list[str]:
    """``format_entities`` of launch's introspector, before tree drawing."""
    out: list[str] = []
    for entity in entities:
        if isinstance(entity, LogInfo):
            out.append(f"LogInfo({_subs(entity.msg)})")
        elif isinstance(entity, EmitEvent):
            out.append(f"EmitEvent(event='{entity.event.name}')")
        elif isinstance(entity, ExecuteProcess) and not isinstance(entity, Node):
            out.append(
                f"ExecuteProcess(cmd=[{', '.join(_subs(c) for c in entity.cmd)}], cwd=None, "
                f"env=None, shell={entity.shell})"
            )
        elif isinstance(entity, RegisterEventHandler):
            out.append(f"RegisterEventHandler('{object_text(entity.event_handler)}'):")
            handler = entity.event_handler
            if hasattr(handler, "describe"):
                text, children = handler.describe()
                out.extend(_indent([text, *_indent(describe_entities(children))]))
        elif isinstance(entity, Action):
            out.append(f"Action('{object_text(entity)}')")
        else:
            out.append(f"Unknown entity('{object_text(entity)}')")
    return out


def _tree(lines: list[str]) -> list[str]:
    result: list[str] = []
    previous: int | None = None
    for old in lines:
        if not old.startswith("    "):
            continue
        line = "│" + old[1:]
        first = len(old) - len(old.lstrip())
        if previous is not None and "└" in result[-1] and previous <= first:
            result[-1] = result[-1].replace("└", "├", 1)
        previous = first
        result.append(line[: first - 4] + "└── " + line[first:])
    if result and result[-1].startswith("│"):
        result[-1] = " " + result[-1][1:]
    return result


def format_print(launch: Ros2Launch) -> str:
    """``ros2 launch --print``: the description tree (addresses shown as ``0x0``)."""
    header = "<launch.launch_description.LaunchDescription object at 0x0>"
    return header + "\n" + "\n".join(_tree(_indent(list(launch.description)))) + "\n"
