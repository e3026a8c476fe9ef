"""A node's command line as ROS reads it: ``rosrun``'s (ROS 1) and ``ros2 run``'s (ROS 2).

ROS 1 (rosgraph.names.load_mappings, rospy's myargv): every ``a:=b`` is a mapping, never an
argument; ``__name``, ``__ns``, ``__master`` (and ``__log``, ``__ip``, ``__hostname``) are
special, ``_param:=value`` sets the private parameter ``~param`` (its value typed as YAML, as
rospy does), anything else is a remap ``from:=to``.

ROS 2 (rcl's arguments.c): after ``--ros-args`` (until ``--``), ``-r/--remap [node:]from:=to``
(``__ns``, ``__node``/``__name`` among them), ``-p/--param [node:]name:=value`` (YAML),
``--params-file FILE``, ``--log-level LEVEL``, ``--log-config-file FILE``, ``-e/--enclave
NAME``, and the ``--enable-``/``--disable-`` logging flags. Other words are the node's own.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from robomodel._escape import escape_name
from robomodel.errors import RobomodelError, close_matches

__all__ = ["NodeArgs", "NodeArgsError", "parse_ros1_args", "parse_ros2_args"]


class NodeArgsError(RobomodelError):
    """A node command line ROS would refuse (a ``--ros-args`` flag without its value, ...)."""


@dataclass(frozen=True, slots=True)
class NodeArgs:
    """What a node's command line sets besides its own arguments."""

    args: tuple[str, ...] = ()
    name: str | None = None
    namespace: str | None = None
    remaps: tuple[tuple[str, str], ...] = ()
    params: dict[str, Any] = field(default_factory=dict)  # ROS 1: private (~name); ROS 2: -p
    params_files: tuple[Path, ...] = ()
    master: str | None = None  # ROS 1 __master:=URI


def _yaml(text: str, where: str) -> Any:
    """A parameter value typed as rospy and rcl type it (YAML; unparsable text stays text)."""
    import yaml

    from robomodel._yaml_bounded import YamlNestingError, load_yaml_file
    from robomodel.launch.ros1.params import RosparamLoader

    try:
        return load_yaml_file(text, where=where, loader=RosparamLoader) if text else ""
    except yaml.YAMLError:
        return text
    except YamlNestingError as exc:
        name = escape_name(where.split(":=", 1)[0])
        raise NodeArgsError(f"the value of '{name}' is refused: {exc.problem}") from None


_ROS1_SPECIAL = ("__name", "__ns", "__master", "__log", "__ip", "__hostname")


def parse_ros1_args(argv: list[str] | tuple[str, ...]) -> NodeArgs:
    """``rosrun PKG TYPE ARGS``' ARGS (see the module docstring)."""
    args: list[str] = []
    remaps: list[tuple[str, str]] = []
    params: dict[str, Any] = {}
    special: dict[str, str] = {}
    for word in argv:
        if ":=" not in word:
            args.append(word)
            continue
        left, _, right = word.partition(":=")
        if left.startswith("__"):
            if left not in _ROS1_SPECIAL:
                hint = close_matches(left, _ROS1_SPECIAL)
                mean = f" (did you mean {hint[0]}?)" if hint else ""
                raise NodeArgsError(
                    f"unknown special argument '{word}'{mean}; ROS 1's are "
                    f"{', '.join(s + ':=' for s in _ROS1_SPECIAL)}"
                )
            special[left] = right
        elif left.startswith("_") and len(left) > 1:
            params[left[1:]] = _yaml(right, word)
        elif left and right:
            remaps.append((left, right))
        else:
            raise NodeArgsError(f"'{word}' is not a remapping: write from:=to")
    return NodeArgs(
        tuple(args),
        special.get("__name"),
        special.get("__ns"),
        tuple(remaps),
        params,
        master=special.get("__master"),
    )


_VALUED = {"--log-level", "--log-config-file", "-e", "--enclave"}  # taken and not used
_FLAGS = {
    "--enable-rosout-logs", "--disable-rosout-logs", "--enable-stdout-logs",
    "--disable-stdout-logs", "--enable-external-lib-logs", "--disable-external-lib-logs",
}  # fmt: skip
_ROS2_OPTIONS = ("-r", "--remap", "-p", "--param", "--params-file", *_VALUED, *_FLAGS)


@dataclass
class _Ros2State:
    args: list[str] = field(default_factory=list)
    remaps: list[tuple[str, str, str | None]] = field(default_factory=list)  # node-scoped
    params: list[tuple[str, Any, str | None]] = field(default_factory=list)
    files: list[Path] = field(default_factory=list)


def _scoped(text: str, word: str) -> tuple[str | None, str, str]:
    """``[node:]left:=right`` -> (node or None, left, right)."""
    left, sep, right = text.partition(":=")
    if not sep or not left:
        raise NodeArgsError(f"'{word} {text}': expected [node:]name:=value")
    node, colon, rest = left.partition(":")
    return (node, rest, right) if colon else (None, left, right)


def _ros2_option(state: _Ros2State, option: str, value: str) -> None:
    if option in ("-r", "--remap"):
        node, left, right = _scoped(value, option)
        state.remaps.append((left, right, node))
    elif option in ("-p", "--param"):
        node, left, right = _scoped(value, option)
        state.params.append((left, _yaml(right, value), node))
    elif option == "--params-file":
        state.files.append(Path(value))


def parse_ros2_args(argv: list[str] | tuple[str, ...], *, default_name: str) -> NodeArgs:
    """``ros2 run PKG EXE ARGS``' ARGS; ``default_name`` picks the node-scoped rules
    (``node:from:=to``) that apply when ``__node`` does not rename it."""
    state = _Ros2State()
    ros = False
    words = list(argv)
    i = 0
    while i < len(words):
        word = words[i]
        if word == "--ros-args":
            ros = True
        elif word == "--" and ros:
            ros = False
        elif not ros:
            state.args.append(word)
        elif word in _FLAGS:
            pass
        elif word in ("-r", "--remap", "-p", "--param", "--params-file", *_VALUED):
            if i + 1 >= len(words):
                raise NodeArgsError(f"--ros-args {word} needs a value")
            _ros2_option(state, word, words[i + 1])
            i += 1
        else:
            hint = close_matches(word, _ROS2_OPTIONS)
            mean = f" (did you mean {hint[0]}?)" if hint else ""
            raise NodeArgsError(
                f"unknown ROS argument '{word}' after --ros-args{mean}; ROS arguments are "
                "-r/--remap, -p/--param, --params-file, --log-level, -e/--enclave (end them "
                "with --)"
            )
        i += 1
    return _ros2_node_args(state, default_name)


def _ros2_node_args(state: _Ros2State, default_name: str) -> NodeArgs:
    special = {left: right for left, right, node in state.remaps if left.startswith("__")}
    name = special.get("__node") or special.get("__name")
    own = name or default_name
    remaps = tuple(
        (left, right)
        for left, right, node in state.remaps
        if not left.startswith("__") and node in (None, own)
    )
    params = {left: value for left, value, node in state.params if node in (None, own)}
    return NodeArgs(
        tuple(state.args),
        name,
        special.get("__ns"),
        remaps,
        params,
        tuple(state.files),
    )
