"""``launch_ros.actions``: Node and the ROS scope actions (namespace, remaps, parameters).

As in launch_ros, the scope state lives in launch configurations (``ros_namespace``,
``ros_remaps``, ``global_params``), so ``GroupAction`` scoping applies to it.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from robomodel.launch.model import NodeSpec, ParamSource
from robomodel.launch.ros2.shim.action import Action
from robomodel.launch.ros2.shim.context import LaunchContext, SubstitutionFailure
from robomodel.launch.ros2.shim.events import ExecuteProcess, record_step
from robomodel.launch.ros2.shim.parameters import (
    Parameter,
    ParameterFile,
    evaluate_dict,
    normalize_dict,
)
from robomodel.launch.ros2.shim.substitutions import (
    coerce_bool,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "Node",
    "PushROSNamespace",
    "PushRosNamespace",
    "SetParameter",
    "SetParametersFromFile",
    "SetRemap",
    "make_namespace_absolute",
    "prefix_namespace",
]


def prefix_namespace(base_ns: str | None, ns: str | None) -> str | None:
    """launch_ros ``prefix_namespace``: ``ns`` under ``base_ns`` unless absolute."""
    combined: str | None = None
    if base_ns is not None or ns is not None:
        if ns is None:
            combined = base_ns
        elif not base_ns or ns.startswith("/"):
            combined = ns
        else:
            combined = ("" if base_ns == "/" else base_ns) + "/" + ns
        if combined is not None and combined != "/":
            combined = combined.rstrip("/")
    return combined


def make_namespace_absolute(ns: str | None) -> str | None:
    """Prefix ``/`` to a relative namespace."""
    if ns is None or ns.startswith("/"):
        return ns
    return "/" + ns


def _validate_namespace(ns: str) -> None:
    if ns == "/":
        return
    for token in ns.strip("/").split("/"):
        if (
            not token
            or not (token[0].isalpha() or token[0] == "_")
            or not all(c.isalnum() or c == "_" for c in token)
        ):
            raise SubstitutionFailure(f"invalid namespace '{ns}'")


class PushRosNamespace(Action):
    """Push a namespace for the nodes that follow in this scope."""

    def __init__(self, namespace: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.namespace = normalize_to_list_of_substitutions(namespace)

    def execute(self, context: LaunchContext) -> list[Any] | None:
        pushed = perform_substitutions(context, self.namespace)
        previous = context.launch_configurations.get("ros_namespace")
        namespace = make_namespace_absolute(prefix_namespace(previous, pushed))
        try:
            _validate_namespace(namespace or "/")
        except SubstitutionFailure:
            raise SubstitutionFailure(
                "The resulting namespace is invalid: "
                f"[previous_namespace='{previous}', pushed_namespace='{pushed}']"
            ) from None
        context.launch_configurations["ros_namespace"] = namespace
        return None


PushROSNamespace = PushRosNamespace


class SetRemap(Action):
    """A remap for the nodes that follow in this scope."""

    def __init__(self, src: Any, dst: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.src = normalize_to_list_of_substitutions(src)
        self.dst = normalize_to_list_of_substitutions(dst)

    def execute(self, context: LaunchContext) -> list[Any] | None:
        src = perform_substitutions(context, self.src)
        dst = perform_substitutions(context, self.dst)
        remaps = context.launch_configurations.get("ros_remaps", [])
        remaps.append((src, dst))  # in place, as launch_ros does
        context.launch_configurations["ros_remaps"] = remaps
        return None


class SetParameter(Action):
    """A parameter for every node that follows in this scope."""

    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        key = tuple(normalize_to_list_of_substitutions(name))
        self.param_dict = normalize_dict({key: value})

    def execute(self, context: LaunchContext) -> list[Any] | None:
        values = evaluate_dict(context, self.param_dict)
        params = context.launch_configurations.get("global_params", [])
        params.extend(values.items())  # in place, as launch_ros does
        context.launch_configurations["global_params"] = params
        return None


class SetParametersFromFile(Action):
    """A parameter file for every node that follows in this scope."""

    def __init__(self, filename: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.filename = normalize_to_list_of_substitutions(filename)

    def execute(self, context: LaunchContext) -> list[Any] | None:
        path = os.path.abspath(perform_substitutions(context, self.filename))
        params = context.launch_configurations.get("global_params", [])
        params.append(path)
        context.launch_configurations["global_params"] = params
        return None


def _normalize_remaps(remappings: Iterable[Any]) -> list[tuple[list[Any], list[Any]]]:
    out = []
    for rule in remappings:
        src, dst = rule
        out.append(
            (normalize_to_list_of_substitutions(src), normalize_to_list_of_substitutions(dst))
        )
    return out


def _normalize_parameters(parameters: Any) -> list[Any]:
    if isinstance(parameters, str) or not isinstance(parameters, Iterable):
        raise TypeError(f"Expecting list of parameters, got {parameters}")
    out: list[Any] = []
    for param in parameters:
        if isinstance(param, Mapping):
            out.append(normalize_dict(param))
        elif isinstance(param, (Parameter, ParameterFile)):
            out.append(param)
        else:
            out.append(ParameterFile(param))
    return out


def _flag(context: LaunchContext, value: Any) -> bool:
    if isinstance(value, bool) or value is None:
        return bool(value)
    return coerce_bool(perform_substitutions(context, normalize_to_list_of_substitutions(value)))


def _seconds(context: LaunchContext, value: Any) -> float:
    if value is None:
        return 0.0
    if isinstance(value, (int, float)):
        return float(value)
    return float(perform_substitutions(context, normalize_to_list_of_substitutions(value)))


class Node(ExecuteProcess):
    """A ROS 2 node (``launch_ros.actions.Node``), recorded as a ``node`` step."""

    def __init__(
        self,
        *,
        executable: Any,
        package: Any = None,
        name: Any = None,
        namespace: Any = None,
        exec_name: Any = None,
        parameters: Any = None,
        remappings: Any = None,
        ros_arguments: Any = None,
        arguments: Any = None,
        **kwargs: Any,
    ) -> None:
        self.node_options = {
            k: kwargs.pop(k) for k in list(kwargs)
            if k in ("respawn", "respawn_delay", "emulate_tty", "prefix", "sigterm_timeout",
                     "sigkill_timeout", "log_cmd", "cached_output", "on_exit", "respawn_max_retries",
                     "required")
        }  # fmt: skip
        super().__init__(cmd=[], name=exec_name, **kwargs)
        self.package = package
        self.executable = executable
        self.node_name = name
        self.node_namespace = namespace
        self.parameters = None if parameters is None else _normalize_parameters(parameters)
        self.remappings = _normalize_remaps(remappings or [])
        self.ros_arguments = list(ros_arguments or [])
        self.arguments = list(arguments or [])

    def _text(self, context: LaunchContext, value: Any) -> str | None:
        if value is None:
            return None
        return perform_substitutions(context, normalize_to_list_of_substitutions(value))

    def _namespace(self, context: LaunchContext) -> str:
        ns = self._text(context, self.node_namespace)
        base = context.launch_configurations.get("ros_namespace")
        full = make_namespace_absolute(prefix_namespace(base, ns)) or "/"
        _validate_namespace(full)
        return full if full.endswith("/") else full + "/"

    def _parameters(self, context: LaunchContext) -> list[ParamSource]:
        out: list[ParamSource] = []
        for item in context.launch_configurations.get("global_params", []):
            if isinstance(item, tuple):
                out.append(ParamSource(values={item[0]: item[1]}))
            else:
                out.append(ParamSource(file=Path(item)))
        for param in self.parameters or []:
            if isinstance(param, ParameterFile):
                path, substituted = param.evaluate(context)
                if not path.is_file():
                    context.session.warn(
                        f"{self.location}: Parameter file path is not a file: {path}"
                    )
                    continue
                out.append(ParamSource(file=path, allow_substs=substituted))
            elif isinstance(param, Parameter):
                name, value = param.evaluate(context)
                out.append(ParamSource(values={name: value}))
            else:
                out.append(ParamSource(values=evaluate_dict(context, param)))
        return out

    def _env(self, context: LaunchContext) -> tuple[tuple[str, str], ...]:
        env = {k: v for k, v in context.env_changes.items() if v is not None}
        for name, value in self.additional_env or []:
            env[self._text(context, name) or ""] = self._text(context, value) or ""
        return tuple(sorted(env.items()))

    def to_spec(self, context: LaunchContext) -> NodeSpec:
        """The node as plain data, substituted in ``context``."""
        remaps = list(context.launch_configurations.get("ros_remaps", []))
        remaps += [
            (perform_substitutions(context, s), perform_substitutions(context, d))
            for s, d in self.remappings
        ]
        options = self.node_options
        extra: dict[str, Any] = {}
        for key in ("emulate_tty", "sigterm_timeout", "sigkill_timeout", "respawn_max_retries"):
            if key in options:
                extra[key] = (
                    options[key]
                    if not isinstance(options[key], (list, str))
                    else self._text(context, options[key])
                )
        exec_name = self._text(context, self.name)
        if exec_name is not None:
            extra["exec_name"] = exec_name
        delay = options.get("respawn_delay")
        return NodeSpec(
            dialect="ros2",
            package=self._text(context, self.package) or "",
            executable=self._text(context, self.executable) or "",
            name=self._text(context, self.node_name),
            namespace=self._namespace(context),
            args=tuple(self._text(context, a) or "" for a in self.arguments),
            remaps=tuple(remaps),
            parameters=tuple(self._parameters(context)),
            env=self._env(context),
            respawn=_flag(context, options.get("respawn", False)),
            respawn_delay_s=_seconds(context, delay),
            output=self._text(context, self.output),
            launch_prefix=self._text(context, options.get("prefix")),
            ros_arguments=tuple(self._text(context, a) or "" for a in self.ros_arguments),
            location=self.location,
            extra=extra,
        )

    def execute(self, context: LaunchContext) -> list[Any] | None:
        spec = self.to_spec(context)
        record_step(context, self, "node", self.location, node=spec)
        return None
