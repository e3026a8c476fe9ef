"""RViz configuration files (``.rviz``, ``-d file.rviz``) read for the browser viewer.

:func:`read_rviz_file` reads the whole file into an :class:`~robomodel.viewer.rviz_model.
RvizConfig`; :func:`settings_of` picks what the viewer applies: Global Options (Fixed Frame,
Frame Rate, Background Color) and the RobotModel's Robot Description (which a launch's rviz
node names for the robot to show). The displays robomodel has (RobotModel, TF, Grid, Marker,
...) are read by :mod:`robomodel.viewer.displays.rviz_io`; every other display class is named
once in the viewer's Status as not supported. Both RViz 1 (``rviz/RobotModel``) and RViz 2
(``rviz_default_plugins/RobotModel``) class names are read.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

import yaml

from robomodel._files import UserFileError, read_user_text
from robomodel._yaml_bounded import YamlNestingError, load_yaml_file
from robomodel.errors import RobomodelError
from robomodel.viewer.displays.base import is_rviz_display
from robomodel.viewer.rviz_model import RvizConfig, RvizDisplay, RvizView, freeze

__all__ = [
    "RvizConfigError",
    "RvizSettings",
    "parse_rviz_text",
    "read_rviz_config",
    "read_rviz_file",
    "settings_of",
]

_GLOBAL_KEYS = ("Fixed Frame", "Frame Rate", "Background Color")


class RvizConfigError(RobomodelError):
    """An .rviz file that cannot be read.

    Attributes:
        missing: The file does not exist (RViz then opens with its defaults).
    """

    def __init__(self, message: str, *, missing: bool = False) -> None:
        super().__init__(message)
        self.missing = missing


@dataclass(frozen=True, slots=True)
class RvizSettings:
    """The parts of an RViz configuration the viewer applies (None: keep the default)."""

    fixed_frame: str | None = None
    frame_rate_hz: float | None = None
    background_rgb: tuple[int, int, int] | None = None
    robot_description: str = "robot_description"
    unsupported: tuple[str, ...] = field(default_factory=tuple)


def _color(text: Any) -> tuple[int, int, int] | None:
    if not isinstance(text, str):
        return None
    try:
        parts = [int(float(p)) for p in text.replace(",", ";").split(";")]
    except ValueError:
        return None
    return (parts[0], parts[1], parts[2]) if len(parts) == 3 else None


def _bool(value: Any) -> bool:
    return value if isinstance(value, bool) else str(value).strip().lower() == "true"


def _is_boolean(value: Any) -> bool:
    return isinstance(value, bool) or str(value).strip().lower() in ("true", "false")


def _number(value: Any, what: str, where: str) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        raise RvizConfigError(f"{where}: {what} must be a number, got {value!r}") from None


def _display(raw: Any, number: int, where: str) -> RvizDisplay:
    if not isinstance(raw, Mapping):
        raise RvizConfigError(f"{where}: Displays entry {number} is not a map of settings")
    settings = dict(raw)
    class_name = str(settings.pop("Class", "") or "")
    name = str(settings.pop("Name", "") or class_name.rsplit("/", 1)[-1])
    # rviz::Display::load: "Value" is the enable property, "Enabled" (when given) overrides it.
    # A Value that is no boolean is dropped, as RViz writes the display's state there on save.
    raw_value = settings.pop("Value", None)
    value = _bool(raw_value) if _is_boolean(raw_value) else None
    enabled = _bool(settings.pop("Enabled")) if "Enabled" in settings else value
    return RvizDisplay(class_name, name, True if enabled is None else enabled, freeze(settings))


def _section(tree: Mapping[str, Any], key: str, where: str) -> dict[str, Any]:
    value = tree.get(key)
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        raise RvizConfigError(f"{where}: '{key}' is not a map of settings")
    return dict(value)


def config_from_tree(data: Any, where: str) -> RvizConfig:
    """An :class:`RvizConfig` from the YAML tree of an .rviz file (``where`` names it)."""
    manager = data.get("Visualization Manager") if isinstance(data, Mapping) else None
    if not isinstance(manager, Mapping):
        raise RvizConfigError(
            f"{where}: no 'Visualization Manager' section (is this a .rviz file?)"
        )
    other, manager = dict(data), dict(manager)
    if manager.get("Class", "") == "":  # RViz always writes it so: the writer puts it back
        manager.pop("Class", None)
    glob = _section(manager, "Global Options", where)
    fixed = glob.pop("Fixed Frame", None)
    rate = glob.pop("Frame Rate", None)
    background = _color(glob.get("Background Color"))
    if background is not None:
        del glob["Background Color"]
    if "Global Options" in manager:
        manager["Global Options"] = glob
    raw_displays = manager.get("Displays") or []
    if not isinstance(raw_displays, list):
        raise RvizConfigError(f"{where}: 'Displays' is not a list of displays")
    displays = tuple(_display(d, i + 1, where) for i, d in enumerate(raw_displays))
    if "Displays" in manager:
        manager["Displays"] = []
    view = None
    if "Views" in manager:
        views = _section(manager, "Views", where)
        current = views.pop("Current", None)
        if isinstance(current, Mapping):
            current = dict(current)
            view = RvizView(str(current.pop("Class", "") or ""), freeze(current))
        manager["Views"] = views
    other["Visualization Manager"] = manager
    return RvizConfig(
        fixed_frame=None if fixed is None else str(fixed),
        frame_rate_hz=None if rate is None else _number(rate, "Frame Rate", where),
        background_rgb=background,
        displays=displays,
        view=view,
        other=MappingProxyType(dict(freeze(other))),
    )


def parse_rviz_text(text: str, where: str) -> RvizConfig:
    """The config in ``text`` (the contents of ``where``)."""
    try:
        data = load_yaml_file(text, where=where) or {}
    except YamlNestingError as exc:
        at = f"{where}:{exc.line}:{exc.column}" if exc.line else where
        raise RvizConfigError(f"{at}: invalid RViz config: {exc.problem}") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        at = f"{where}:{mark.line + 1}:{mark.column + 1}" if mark else where
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]  # one line
        raise RvizConfigError(f"{at}: invalid RViz config: {problem}") from None
    return config_from_tree(data, where)


def read_rviz_file(path: str | Path) -> RvizConfig:
    """The whole config of an .rviz file.

    Raises:
        RvizConfigError: unreadable or not an RViz config; ``missing`` when it does not exist.
    """
    try:
        text = read_user_text(path, what="RViz config")
    except UserFileError as exc:
        raise RvizConfigError(str(exc), missing=exc.errno == 2) from None
    return parse_rviz_text(text, str(path))


def _description(display: RvizDisplay) -> str | None:
    found = display.settings.get("Robot Description") or display.settings.get("Description Topic")
    if isinstance(found, str) and found:
        return found
    if isinstance(found, Mapping) and found.get("Value"):
        return str(found["Value"]).lstrip("/")
    return None


def settings_of(config: RvizConfig) -> RvizSettings:
    """What the viewer applies from ``config`` (the last display of each kind counts)."""
    values: dict[str, Any] = {
        "fixed_frame": config.fixed_frame,
        "frame_rate_hz": config.frame_rate_hz,
        "background_rgb": config.background_rgb,
    }
    unsupported: list[str] = []
    for display in config.displays:
        if display.kind == "RobotModel":
            values["robot_description"] = _description(display) or "robot_description"
        elif not is_rviz_display(display.class_name) and display.class_name not in unsupported:
            unsupported.append(display.class_name or "?")
    return RvizSettings(unsupported=tuple(unsupported), **values)


def read_rviz_config(path: str | Path) -> RvizSettings:
    """Read the settings robomodel applies from an RViz config file."""
    return settings_of(read_rviz_file(path))
