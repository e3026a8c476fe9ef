"""The upstream module names the import hook provides, and what each one holds."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ["MODULES"]


def _pick(module: Any, *names: str) -> dict[str, Any]:
    return {name: getattr(module, name) for name in names}


def _substitutions() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import commands, logic, substitutions

    out = _pick(substitutions, *substitutions.__all__)
    out.update(_pick(logic, *logic.__all__))
    out.update(_pick(commands, "Command", "PythonExpression"))
    return out


def _actions() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import actions, events

    out = _pick(actions, *actions.__all__)
    out.update(
        _pick(
            events,
            "EmitEvent",
            "ExecuteProcess",
            "LogInfo",
            "RegisterEventHandler",
            "Shutdown",
            "TimerAction",
        )
    )
    out["ExecuteLocal"] = events.ExecuteProcess
    return out


def _launch() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import action, conditions, context, substitutions

    out = _pick(action, "Action", "LaunchDescription", "LaunchDescriptionEntity")
    out["LaunchContext"] = context.LaunchContext
    out["Substitution"] = substitutions.Substitution
    out["Condition"] = conditions.Condition
    out["SomeSubstitutionsType"] = Any
    out["SomeActionsType"] = Any
    return out


def _conditions() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import conditions

    return _pick(conditions, *conditions.__all__)


def _event_handlers() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import events

    out = _pick(events, "OnProcessExit", "OnProcessStart")
    for name in ("OnProcessIO", "OnShutdown", "OnExecutionComplete", "OnIncludeLaunchDescription"):
        out[name] = events.unsupported_handler(name)
    return out


def _events() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import events

    return {"Shutdown": events.ShutdownEvent}


def _sources() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import sources

    upstream = [n for n in sources.__all__ if n.endswith("LaunchDescriptionSource")]
    return _pick(sources, *upstream)


def _utilities() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import substitutions

    return _pick(
        substitutions, "normalize_to_list_of_substitutions", "perform_substitutions",
        "perform_typed_substitution",
    )  # fmt: skip


def _ros_actions() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import ros

    return _pick(
        ros, "Node", "PushRosNamespace", "PushROSNamespace", "SetParameter",
        "SetParametersFromFile", "SetRemap",
    )  # fmt: skip


def _ros_substitutions() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import commands

    return _pick(
        commands, "FindPackage", "FindPackagePrefix", "FindPackageShare", "ExecutableInPackage"
    )


def _parameter_descriptions() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import parameters

    return _pick(parameters, "Parameter", "ParameterFile", "ParameterValue")


def _ament_packages() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import commands

    return _pick(
        commands, "PackageNotFoundError", "get_package_prefix", "get_package_share_directory",
        "get_package_share_path",
    )  # fmt: skip


def _xacro() -> dict[str, Any]:
    from robomodel.launch.ros2.shim import xacro_api

    return _pick(xacro_api, "parse", "process_doc", "process_file")


def _empty() -> dict[str, Any]:
    return {}


def _process_events() -> dict[str, Any]:
    return {}


MODULES: dict[str, Callable[[], dict[str, Any]]] = {
    "launch": _launch,
    "launch.actions": _actions,
    "launch.substitutions": _substitutions,
    "launch.conditions": _conditions,
    "launch.event_handlers": _event_handlers,
    "launch.events": _events,
    "launch.events.process": _process_events,
    "launch.launch_description_sources": _sources,
    "launch.some_substitutions_type": lambda: {"SomeSubstitutionsType": Any},
    "launch.launch_context": lambda: _pick(
        __import__("robomodel.launch.ros2.shim.context", fromlist=["x"]), "LaunchContext"
    ),
    "launch.launch_description": lambda: {"LaunchDescription": _launch()["LaunchDescription"]},
    "launch.utilities": _utilities,
    "launch_xml": _empty,
    "launch_xml.launch_description_sources": lambda: {
        "XMLLaunchDescriptionSource": _sources()["XMLLaunchDescriptionSource"]
    },
    "launch_yaml": _empty,
    "launch_yaml.launch_description_sources": lambda: {
        "YAMLLaunchDescriptionSource": _sources()["YAMLLaunchDescriptionSource"]
    },
    "launch_ros": _empty,
    "launch_ros.actions": _ros_actions,
    "launch_ros.substitutions": _ros_substitutions,
    "launch_ros.parameter_descriptions": _parameter_descriptions,
    "launch_ros.descriptions": _parameter_descriptions,
    "ament_index_python": _ament_packages,
    "ament_index_python.packages": _ament_packages,
    "xacro": _xacro,
}
