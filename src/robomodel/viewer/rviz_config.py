"""RViz configuration files (``.rviz``, ``-d file.rviz``) read for the browser viewer.

What is applied: Global Options (Fixed Frame, Frame Rate, Background Color), the RobotModel
display (Enabled, Alpha, Visual Enabled, Collision Enabled, Robot Description) and the TF
display (Enabled, Show Axes, Show Names, Marker Scale), the Grid display (Enabled). Every
other display class is named once in the viewer's Status as not supported. Both RViz 1
(``rviz/RobotModel``) and RViz 2 (``rviz_default_plugins/RobotModel``) class names are read.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from robomodel._files import UserFileError, read_user_text
from robomodel.errors import RobomodelError

__all__ = ["RvizConfigError", "RvizSettings", "read_rviz_config"]

_SUPPORTED = {"RobotModel", "TF", "Grid"}


class RvizConfigError(RobomodelError):
    """An .rviz file that cannot be read."""


@dataclass(frozen=True, slots=True)
class RvizSettings:
    """The parts of an RViz configuration the viewer applies (None: keep the default)."""

    fixed_frame: str | None = None
    frame_rate_hz: float | None = None
    background_rgb: tuple[int, int, int] | None = None
    robot_model_enabled: bool = True
    robot_description: str = "robot_description"
    alpha: float | None = None
    visual_enabled: bool | None = None
    collision_enabled: bool | None = None
    tf_enabled: bool = True
    tf_show_axes: bool | None = None
    tf_show_names: bool | None = None
    tf_marker_scale: float | None = None
    grid_enabled: bool | None = None
    unsupported: tuple[str, ...] = field(default_factory=tuple)


def _color(text: Any) -> tuple[int, int, int] | None:
    if not isinstance(text, str):
        return None
    try:
        parts = [int(float(p)) for p in text.replace(",", ";").split(";")]
    except ValueError:
        return None
    return (parts[0], parts[1], parts[2]) if len(parts) >= 3 else None


def _kind(display: dict[str, Any]) -> str:
    return str(display.get("Class", "")).rsplit("/", 1)[-1]


def read_rviz_config(path: str | Path) -> RvizSettings:
    """Read the settings robomodel applies from an RViz config file."""
    try:
        data = yaml.safe_load(read_user_text(path, what="RViz config")) or {}
    except UserFileError as exc:
        raise RvizConfigError(str(exc)) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{path}:{mark.line + 1}:{mark.column + 1}" if mark else str(path)
        raise RvizConfigError(f"{where}: invalid RViz config: {exc}") from None
    manager = data.get("Visualization Manager") if isinstance(data, dict) else None
    if not isinstance(manager, dict):
        raise RvizConfigError(f"{path}: no 'Visualization Manager' section (is this a .rviz file?)")
    glob = manager.get("Global Options") or {}
    displays = [d for d in manager.get("Displays") or [] if isinstance(d, dict)]
    settings: dict[str, Any] = {
        "fixed_frame": glob.get("Fixed Frame"),
        "frame_rate_hz": float(glob["Frame Rate"]) if "Frame Rate" in glob else None,
        "background_rgb": _color(glob.get("Background Color")),
        "robot_model_enabled": False,
        "tf_enabled": False,
    }
    unsupported: list[str] = []
    for display in displays:
        kind = _kind(display)
        enabled = bool(display.get("Enabled", True))
        if kind == "RobotModel":
            settings["robot_model_enabled"] = enabled
            settings["alpha"] = float(display["Alpha"]) if "Alpha" in display else None
            settings["visual_enabled"] = display.get("Visual Enabled")
            settings["collision_enabled"] = display.get("Collision Enabled")
            description = display.get("Robot Description") or display.get("Description Topic")
            if isinstance(description, str) and description:
                settings["robot_description"] = description
            elif isinstance(description, dict) and description.get("Value"):
                settings["robot_description"] = str(description["Value"]).lstrip("/")
        elif kind == "TF":
            settings["tf_enabled"] = enabled
            settings["tf_show_axes"] = display.get("Show Axes")
            settings["tf_show_names"] = display.get("Show Names")
            if "Marker Scale" in display:
                settings["tf_marker_scale"] = float(display["Marker Scale"])
        elif kind == "Grid":
            settings["grid_enabled"] = enabled
        elif kind not in _SUPPORTED:
            name = str(display.get("Class", "?"))
            if name not in unsupported:
                unsupported.append(name)
    return RvizSettings(unsupported=tuple(unsupported), **settings)
