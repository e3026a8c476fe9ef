"""The viewer's RViz config: the ``-d`` file (read, or RViz's defaults when it does not exist
yet) and where Save Config writes it.

RViz opens with its default config when ``-d`` names a file that does not exist, and its Save
Config then writes that file (``rviz::VisualizationFrame``: ``display_config_file_`` is the
``-d`` path). robomodel does the same, its defaults being RViz's (a Grid) plus the RobotModel
and TF displays the viewer draws anyway; the seeds' "add RobotModel and TF, set the Fixed
Frame, save as urdf.rviz" step is then one click.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from pathlib import Path

from robomodel.viewer.rviz_config import (
    RvizConfigError,
    RvizSettings,
    parse_rviz_text,
    read_rviz_file,
    settings_of,
)
from robomodel.viewer.rviz_model import RvizConfig, RvizDialect

__all__ = ["RvizDocument", "default_rviz_config", "open_rviz_document"]

_DEFAULTS = Path(__file__).with_name("rviz_defaults")


@functools.cache
def default_rviz_config(dialect: RvizDialect) -> RvizConfig:
    """RViz's default config (its Grid) with RobotModel and TF, in ``dialect``'s class names.

    Transcribed from RViz's own default.rviz (rviz 1.14, ros2/rviz rviz_common); see the
    header of ``rviz_defaults/<dialect>.rviz``.
    """
    path = _DEFAULTS / f"{dialect.value}.rviz"
    return parse_rviz_text(path.read_text(encoding="utf-8"), str(path))


@dataclass(frozen=True, slots=True)
class RvizDocument:
    """The config the viewer opened and where Save Config writes it.

    Attributes:
        path: The ``-d`` file (None: none given; Save Config asks for a path).
        config: The config read, or the defaults when ``missing``.
        dialect: The class names of displays the viewer adds (the file's own when it has
            any, else the launch's ROS version).
        missing: No file was read (none given, or ``path`` did not exist when the viewer
            opened): the view and background are robomodel's (the camera fitted to the
            robot), not the defaults' 10 m orbit.
    """

    path: str | None
    config: RvizConfig
    dialect: RvizDialect
    missing: bool = False

    @property
    def settings(self) -> RvizSettings:
        """What the viewer applies (see :func:`~robomodel.viewer.rviz_config.settings_of`)."""
        return settings_of(self.config)


def open_rviz_document(path: str | None, dialect: RvizDialect) -> tuple[RvizDocument, str | None]:
    """The document for ``-d path`` and, when the file does not exist, the one warning line.

    Raises:
        RvizConfigError: the file exists but cannot be read or is not an RViz config.
    """
    if path is None:
        return RvizDocument(None, default_rviz_config(dialect), dialect, missing=True), None
    try:
        config = read_rviz_file(path)
    except RvizConfigError as exc:
        if not exc.missing:
            raise
        warning = (
            f"RViz config {path} does not exist: opening RViz's default displays (Grid) with "
            "RobotModel and TF; Save Config in the viewer writes it"
        )
        return RvizDocument(path, default_rviz_config(dialect), dialect, missing=True), warning
    return RvizDocument(path, config, config.dialect or dialect), None
