"""Front-end entities (XML or YAML) to launch actions, as each action's upstream ``parse``."""

from __future__ import annotations

import shlex
from collections.abc import Callable
from typing import Any

from robomodel.errors import SourceLocation
from robomodel.launch.model import LaunchError
from robomodel.launch.ros2.frontend.entity import Entity, FrontendError
from robomodel.launch.ros2.frontend.substitution_parser import parse_substitution
from robomodel.launch.ros2.shim import actions as a
from robomodel.launch.ros2.shim import events as ev
from robomodel.launch.ros2.shim import ros
from robomodel.launch.ros2.shim.action import LaunchDescription
from robomodel.launch.ros2.shim.conditions import IfCondition, UnlessCondition
from robomodel.launch.ros2.shim.context import SubstitutionFailure, current_session
from robomodel.launch.ros2.shim.parameters import ParameterFile, ParameterValue
from robomodel.launch.ros2.shim.substitutions import Substitution, TextSubstitution

__all__ = ["build_description"]

Builder = Callable[[Entity, dict[str, Any]], Any]


def _subs(value: Any) -> Any:
    if isinstance(value, str):
        return parse_substitution(value)
    if isinstance(value, (bool, int, float)):
        return parse_substitution(str(value).lower() if isinstance(value, bool) else str(value))
    return value


def _cmdline(value: str) -> list[list[Substitution]]:
    """Split a command line into tokens of substitutions (launch's ``_parse_cmdline``)."""
    result: list[list[Substitution]] = []
    arg: list[Substitution] = []
    for sub in parse_substitution(value):
        if not isinstance(sub, TextSubstitution):
            arg.append(sub)
            continue
        try:
            tokens = shlex.split(sub.text)
        except ValueError as exc:
            raise ValueError(f"cannot split command line '{value}': {exc}") from None
        if not tokens:
            result.append(arg)
            arg = []
            continue
        if sub.text[0].isspace() and arg:
            result.append(arg)
            arg = []
        arg.append(TextSubstitution(text=tokens[0]))
        if len(tokens) > 1:
            result.append(arg)
            arg = [TextSubstitution(text=tokens[-1])]
        if len(tokens) > 2:
            result.extend([TextSubstitution(text=x)] for x in tokens[1:-1])
        if sub.text[-1].isspace():
            result.append(arg)
            arg = []
    if arg:
        result.append(arg)
    return result


def _arg(e: Entity, kw: dict[str, Any]) -> Any:
    e.check_attributes(("name", "default", "description"))
    choices = [str(c.get("value", optional=False)) for c in e.entities("choice")] or None
    default = e.get("default")
    return a.DeclareLaunchArgument(
        str(e.get("name", optional=False)),
        default_value=None if default is None else _subs(default),
        description=e.get("description"),
        choices=choices,
        **kw,
    )


def _let(e: Entity, kw: dict[str, Any]) -> Any:
    e.check_attributes(("name", "value"))
    return a.SetLaunchConfiguration(
        _subs(e.get("name", optional=False)), _subs(e.get("value", optional=False)), **kw
    )


def _nested_params(params: list[Entity]) -> dict[Any, Any]:
    out: dict[Any, Any] = {}
    for p in params:
        name = tuple(_subs(p.get("name", optional=False)))
        value = p.get("value")
        nested = p.entities("param")
        sep = p.get("value-sep")
        if value is not None and nested:
            raise p.error("nested parameters and value attributes are mutually exclusive")
        if value is not None:
            if sep is not None and isinstance(value, str):
                out[name] = ParameterValue([_subs(v) for v in value.split(sep)])
            else:
                out[name] = ParameterValue(_subs(value) if isinstance(value, str) else value)
        elif nested:
            out[name] = _nested_params(nested)
        else:
            raise p.error("either a value attribute or nested params are needed")
    return out


def _parameters(params: list[Entity]) -> list[Any]:
    out: list[Any] = []
    for p in params:
        source, name = p.get("from"), p.get("name")
        if source is not None and name is not None:
            raise p.error("name and from attributes are mutually exclusive")
        if source is not None:
            allow = p.get("allow_substs")
            out.append(
                ParameterFile(
                    _subs(source),
                    allow_substs=_subs(allow) if isinstance(allow, str) else bool(allow),
                )
            )
        elif name is not None:
            if p.get("allow_substs") is not None:
                raise p.error("'allow_substs' can only be used together with 'from' attribute")
            out.append(_nested_params([p]))
        else:
            raise p.error("param Entity should have name or from attribute")
    return out


def _env(e: Entity) -> list[tuple[Any, Any]]:
    return [
        (_subs(x.get("name", optional=False)), _subs(x.get("value", optional=False)))
        for x in e.entities("env")
    ]


def _node(e: Entity, kw: dict[str, Any]) -> Any:
    e.check_attributes(("pkg", "exec", "name", "node-name", "namespace", "ns", "args", "ros_args", "output",
                        "respawn", "respawn_delay", "launch-prefix", "exec_name", "emulate_tty", "cwd"))  # fmt: skip
    if e.type_name in ("node_container", "load_composable_node", "composable_node"):
        raise e.error(f"<{e.type_name}> (composable nodes) is not supported by robomodel launch")
    args, ros_args = e.get("args"), e.get("ros_args")
    namespace = e.get("namespace") if e.get("namespace") is not None else e.get("ns")
    name = e.get("name") if e.get("name") is not None else e.get("node-name")
    options = {
        k.replace("launch-prefix", "prefix"): _subs(e.get(k))
        for k in ("respawn", "respawn_delay", "launch-prefix")
        if e.get(k) is not None
    }
    return ros.Node(
        package=_subs(e.get("pkg")),
        executable=_subs(e.get("exec", optional=False)),
        name=None if name is None else _subs(name),
        namespace=None if namespace is None else _subs(namespace),
        exec_name=None if e.get("exec_name") is None else _subs(e.get("exec_name")),
        arguments=_cmdline(str(args)) if args is not None else None,
        ros_arguments=_cmdline(str(ros_args)) if ros_args is not None else None,
        remappings=[
            (_subs(r.get("from", optional=False)), _subs(r.get("to", optional=False)))
            for r in e.entities("remap")
        ],
        parameters=_parameters(e.entities("param")) or None,
        output=_subs(e.get("output") or "log"),
        additional_env=_env(e) or None,
        **options,
        **kw,
    )


def _executable(e: Entity, kw: dict[str, Any]) -> Any:
    e.check_attributes(("cmd", "name", "cwd", "shell", "output", "launch-prefix", "emulate_tty"))
    return ev.ExecuteProcess(
        cmd=_cmdline(str(e.get("cmd", optional=False))), name=e.get("name"), cwd=e.get("cwd"),
        shell=bool(e.get_bool("shell")), output=e.get("output") or "log", additional_env=_env(e) or None, **kw,
    )  # fmt: skip


def _include(e: Entity, kw: dict[str, Any]) -> Any:
    e.check_attributes(("file",))
    arguments = [
        (_subs(x.get("name", optional=False)), _subs(x.get("value", optional=False)))
        for x in e.entities("arg")
    ]
    return a.IncludeLaunchDescription(
        _subs(e.get("file", optional=False)), launch_arguments=arguments, **kw
    )


def _group(e: Entity, kw: dict[str, Any]) -> Any:
    e.check_attributes(("scoped", "forwarding", "ns", "namespace"))
    scoped, forwarding = e.get_bool("scoped"), e.get_bool("forwarding")
    keeps = {
        tuple(_subs(k.get("name", optional=False))): _subs(k.get("value", optional=False))
        for k in e.entities("keep")
    }
    children = build_actions([c for c in e.children if c.type_name != "keep"])
    ns = e.get("ns") if e.get("ns") is not None else e.get("namespace")
    if ns is not None:
        children.insert(0, ros.PushRosNamespace(_subs(ns)))
    return a.GroupAction(
        children, scoped=True if scoped is None else scoped,
        forwarding=True if forwarding is None else forwarding, launch_configurations=keeps, **kw,
    )  # fmt: skip


def _timer(e: Entity, kw: dict[str, Any]) -> Any:
    e.check_attributes(("period",))
    return ev.TimerAction(
        period=_subs(e.get("period", optional=False)), actions=build_actions(e.children), **kw
    )


def _simple(e: Entity, kw: dict[str, Any]) -> Any:
    t = e.type_name
    if t == "log":
        e.check_attributes(("message",))
        return ev.LogInfo(msg=_subs(e.get("message", optional=False)), **kw)
    if t == "shutdown":
        e.check_attributes(("reason",))
        return ev.Shutdown(reason=_subs(e.get("reason") or "reason not given"), **kw)
    if t in ("push-ros-namespace", "push_ros_namespace"):
        e.check_attributes(("namespace",))
        return ros.PushRosNamespace(_subs(e.get("namespace", optional=False)), **kw)
    if t in ("set_parameter", "set-parameter"):
        e.check_attributes(("name", "value"))
        return ros.SetParameter(
            _subs(e.get("name", optional=False)), _subs(e.get("value", optional=False)), **kw
        )
    if t in ("set_remap", "set-remap"):
        e.check_attributes(("from", "to"))
        return ros.SetRemap(
            _subs(e.get("from", optional=False)), _subs(e.get("to", optional=False)), **kw
        )
    if t == "set_parameters_from_file":
        e.check_attributes(("filename",))
        return ros.SetParametersFromFile(_subs(e.get("filename", optional=False)), **kw)
    if t == "set_env":
        e.check_attributes(("name", "value"))
        return a.SetEnvironmentVariable(
            _subs(e.get("name", optional=False)), _subs(e.get("value", optional=False)), **kw
        )
    if t == "unset_env":
        e.check_attributes(("name",))
        return a.UnsetEnvironmentVariable(_subs(e.get("name", optional=False)), **kw)
    if t == "append_env":
        e.check_attributes(("name", "value", "prepend", "separator"))
        return a.AppendEnvironmentVariable(
            _subs(e.get("name", optional=False)), _subs(e.get("value", optional=False)),
            prepend=bool(e.get_bool("prepend")), separator=e.get("separator") or ":", **kw,
        )  # fmt: skip
    raise e.error(f"unknown tag <{t}>; known: {', '.join(sorted(BUILDERS))}")


BUILDERS: dict[str, Builder] = {
    "arg": _arg, "let": _let, "node": _node, "executable": _executable, "include": _include,
    "group": _group, "timer": _timer, "node_container": _node, "load_composable_node": _node,
    **{t: _simple for t in ("log", "shutdown", "push-ros-namespace", "push_ros_namespace",
                            "set_parameter", "set-parameter", "set_remap", "set-remap",
                            "set_parameters_from_file", "set_env", "unset_env", "append_env")},
}  # fmt: skip


def _build(e: Entity) -> Any:
    kw: dict[str, Any] = {}
    if e.get("if") is not None and e.get("unless") is not None:
        raise e.error("if and unless attributes are mutually exclusive")
    if e.get("if") is not None:
        kw["condition"] = IfCondition(_subs(e.get("if")))
    elif e.get("unless") is not None:
        kw["condition"] = UnlessCondition(_subs(e.get("unless")))
    action = BUILDERS.get(e.type_name, _simple)(e, kw)
    action.location = e.location
    return action


def build_actions(entities: list[Entity]) -> list[Any]:
    """Actions for ``entities`` in order; errors are LaunchError at the element."""
    out = []
    for e in entities:
        try:
            out.append(_build(e))
        except FrontendError as exc:
            raise _error(str(exc), exc.location) from None
        except (SubstitutionFailure, ValueError, TypeError, RuntimeError) as exc:
            raise _error(str(exc), e.location) from None
    return out


def _error(message: str, location: SourceLocation | None) -> LaunchError:
    session = current_session()
    return LaunchError(
        message, location=location, include_stack=tuple(session.include_stack) if session else ()
    )


def build_description(entities: list[Entity], location: SourceLocation) -> LaunchDescription:
    """A LaunchDescription of the top-level entities."""
    description = LaunchDescription(build_actions(entities))
    description.location = location
    return description
