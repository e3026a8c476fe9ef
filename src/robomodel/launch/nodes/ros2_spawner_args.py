"""The ROS 2 ``spawner``'s command line (Humble and Jazzy), with Jazzy's timeout defaults."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from robomodel.errors import RobomodelError

__all__ = ["Ros2SpawnerArgs", "parse_ros2_spawner_args"]


@dataclass(frozen=True, slots=True)
class Ros2SpawnerArgs:
    """controller_manager's ``spawner`` command line (Humble and Jazzy; ``-p`` may repeat)."""

    controllers: tuple[str, ...]
    controller_manager: str = "controller_manager"
    param_files: tuple[str, ...] = ()
    inactive: bool = False
    load_only: bool = False
    activate_as_group: bool = False
    unload_on_kill: bool = False
    controller_type: str | None = None
    timeout_s: float = 0.0
    service_call_timeout_s: float = 10.0
    switch_timeout_s: float = 5.0
    namespace: str | None = None


# Jazzy's spawner.py (ros2_control 4.x, controller_manager/spawner.py and
# controller_manager_services.py service_caller): --controller-manager-timeout 0.0 (wait for
# the services forever, warning every 10 s), --service-call-timeout 10.0 (each call, up to 3
# attempts), --switch-timeout 5.0.
_VALUED = {
    "-c": "controller_manager", "--controller-manager": "controller_manager",
    "-p": "param_files", "--param-file": "param_files",
    "-t": "controller_type", "--controller-type": "controller_type",
    "--controller-manager-timeout": "timeout_s", "--switch-timeout": "switch_timeout_s",
    "--service-call-timeout": "service_call_timeout_s", "-n": "namespace",
    "--namespace": "namespace", "--controller-ros-args": None,
}  # fmt: skip
_SECONDS = ("timeout_s", "switch_timeout_s", "service_call_timeout_s")
_FLAGS: dict[str, str | None] = {
    "--inactive": "inactive", "--stopped": "inactive", "--load-only": "load_only",
    "--activate-as-group": "activate_as_group", "-u": "unload_on_kill",
    "--unload-on-kill": "unload_on_kill", "--switch-asap": None, "--no-switch-asap": None,
}  # fmt: skip


def parse_ros2_spawner_args(args: tuple[str, ...]) -> Ros2SpawnerArgs:
    """The spawner's options; RobomodelError names an unknown one."""
    names: list[str] = []
    values: dict[str, Any] = {}
    words = list(args)
    if "--ros-args" in words:
        words = words[: words.index("--ros-args")]
    i = 0
    while i < len(words):
        word = words[i]
        option, eq, inline = word.partition("=")
        if option in _VALUED:
            if not eq:
                if i + 1 >= len(words):
                    raise RobomodelError(f"spawner: {option} needs a value")
                inline = words[i + 1]
                i += 1
            key = _VALUED[option]
            if key == "param_files":
                values[key] = (*values.get(key, ()), inline)
            elif key is not None:
                values[key] = inline
        elif word in _FLAGS:
            flag = _FLAGS[word]
            if flag is not None:
                values[flag] = True
        elif word.startswith("-"):
            raise RobomodelError(
                f"spawner: unrecognized arguments: {word} (options: -c/--controller-manager, "
                "-p/--param-file, --inactive, --load-only, --activate-as-group, "
                "-u/--unload-on-kill, --controller-manager-timeout, --controller-ros-args, "
                "--switch-asap)"
            )
        else:
            names.append(word)
        i += 1
    if not names:
        raise RobomodelError("spawner: the following arguments are required: controller_names")
    for key in _SECONDS:
        if key in values:
            try:
                values[key] = float(values[key])
            except ValueError:
                option = next(o for o, k in _VALUED.items() if k == key)
                raise RobomodelError(
                    f"spawner: argument {option}: invalid float value: '{values[key]}'"
                ) from None
    return Ros2SpawnerArgs(tuple(names), **values)
