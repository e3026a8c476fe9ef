"""Write an :class:`~robomodel.viewer.rviz_model.RvizConfig` as an ``.rviz`` file RViz opens.

The layout is RViz's own (see :mod:`robomodel.viewer.rviz_yaml`): ``Panels``,
``Visualization Manager`` (``Class: ""``, ``Displays`` each with ``Class``, ``Enabled``,
``Name``, ``Value`` and its settings, ``Global Options``, ``Tools``, ``Views``), ``Window
Geometry``. Files are written atomically: a temporary file beside the target, then
``os.replace``, so a reader never sees half a file and a failed save leaves the old one.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.viewer.rviz_model import RvizConfig, RvizDisplay, thaw
from robomodel.viewer.rviz_yaml import dump_rviz_yaml

__all__ = ["RvizSaveError", "rviz_text", "rviz_tree", "write_rviz_config"]


class RvizSaveError(RobomodelError):
    """An .rviz file that could not be written (the message names the path and why)."""


def _display_tree(display: RvizDisplay) -> dict[str, Any]:
    tree: dict[str, Any] = thaw(display.settings)
    # RViz writes the enable state twice: the display's own property (Value) and Enabled.
    tree.update(
        {"Class": display.class_name, "Name": display.name, "Enabled": display.enabled,
         "Value": display.enabled}
    )  # fmt: skip
    return tree


def rviz_tree(config: RvizConfig) -> dict[str, Any]:
    """The YAML tree of ``config``: its ``other`` parts with the modelled ones put back."""
    tree: dict[str, Any] = thaw(config.other)
    manager = tree.setdefault("Visualization Manager", {})
    manager.setdefault("Class", "")
    glob = manager.get("Global Options") or {}
    if config.fixed_frame is not None:
        glob["Fixed Frame"] = config.fixed_frame
    if config.frame_rate_hz is not None:
        glob["Frame Rate"] = config.frame_rate_hz
    if config.background_rgb is not None:
        glob["Background Color"] = "; ".join(str(c) for c in config.background_rgb)
    if glob or "Global Options" in manager:
        manager["Global Options"] = glob
    if config.displays or "Displays" in manager:
        manager["Displays"] = [_display_tree(d) for d in config.displays]
    if config.view is not None:
        views = manager.get("Views") or {}
        views["Current"] = {**thaw(config.view.settings), "Class": config.view.class_name}
        manager["Views"] = views
    return tree


def rviz_text(config: RvizConfig) -> str:
    """The text of the .rviz file holding ``config``."""
    return dump_rviz_yaml(rviz_tree(config))


def write_rviz_config(path: str | Path, config: RvizConfig) -> Path:
    """Write ``config`` to ``path`` (``~`` expanded; missing parent folders are made, as the
    student saving ``config/view_urdf.rviz`` into a new package needs); the path written.

    Raises:
        RvizSaveError: the folder or file cannot be written (permissions, a directory there).
    """
    target = Path(path).expanduser()
    text = rviz_text(config)
    if target.is_dir():
        raise RvizSaveError(f"cannot save RViz config to {target}: it is a directory")
    temp = None
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        handle, temp = tempfile.mkstemp(prefix=f".{target.name}.", dir=target.parent)
        with os.fdopen(handle, "w", encoding="utf-8") as out:
            out.write(text)
        os.chmod(temp, target.stat().st_mode & 0o7777 if target.exists() else 0o644)
        os.replace(temp, target)
    except OSError as exc:
        if temp is not None:
            Path(temp).unlink(missing_ok=True)
        reason = exc.strerror or str(exc)
        raise RvizSaveError(f"cannot save RViz config to {target}: {reason}") from None
    return target.absolute()
