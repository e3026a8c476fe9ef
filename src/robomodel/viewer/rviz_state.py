"""What the viewer shows, as RViz's config holds it, both ways.

:func:`implied_state` is what a config makes the viewer show (as RViz would start with it);
:func:`config_with_state` is the config that saves what the viewer shows now. Only what
differs from the config's implied state is written back, so opening a file and saving it
unchanged rewrites the same file, and a display the viewer cannot show keeps its settings.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import Any

from robomodel.viewer.rviz_document import RvizDocument, default_rviz_config
from robomodel.viewer.rviz_model import RvizConfig, RvizView

__all__ = ["OrbitCamera", "ViewerState", "config_with_state", "implied_state", "orbit_of"]

_ANGLE_TOLERANCE_RAD = 1e-4  # a browser's camera is float32; an untouched view stays put
_LENGTH_TOLERANCE_M = 1e-4


def _round(value: float) -> float:
    """6 significant digits: RViz's float properties print so (``0.785398``)."""
    return float(f"{value:.6g}")


@dataclass(frozen=True, slots=True)
class OrbitCamera:
    """RViz's Orbit view: the camera at ``distance_m`` from the focal point, ``yaw_rad``
    about +z from +x and ``pitch_rad`` up (rviz OrbitViewController::updateCamera)."""

    focal_point_m: tuple[float, float, float]
    distance_m: float
    yaw_rad: float
    pitch_rad: float

    def position_m(self) -> tuple[float, float, float]:
        d, yaw, pitch = self.distance_m, self.yaw_rad, self.pitch_rad
        fx, fy, fz = self.focal_point_m
        return (
            fx + d * math.cos(yaw) * math.cos(pitch),
            fy + d * math.sin(yaw) * math.cos(pitch),
            fz + d * math.sin(pitch),
        )

    @classmethod
    def looking(cls, position_m: Any, look_at_m: Any) -> OrbitCamera:
        """From a camera position and its look-at point (calculatePitchYawFromPosition;
        yaw in [0, 2 pi) as OrbitViewController::yaw keeps it)."""
        focal = tuple(float(v) for v in look_at_m)
        dx, dy, dz = (float(p) - f for p, f in zip(position_m, focal, strict=True))
        distance = math.sqrt(dx * dx + dy * dy + dz * dz)
        pitch = math.asin(max(-1.0, min(1.0, dz / distance))) if distance > 0 else 0.0
        yaw = math.atan2(dy, dx) % (2 * math.pi)
        return cls(
            (_round(focal[0]), _round(focal[1]), _round(focal[2])),
            _round(distance),
            _round(yaw),
            _round(pitch),
        )

    def close_to(self, other: OrbitCamera | None) -> bool:
        if other is None:
            return False
        lengths = [*self.focal_point_m, self.distance_m]
        others = [*other.focal_point_m, other.distance_m]
        yaw = abs((self.yaw_rad - other.yaw_rad + math.pi) % (2 * math.pi) - math.pi)
        return (
            all(abs(a - b) <= _LENGTH_TOLERANCE_M for a, b in zip(lengths, others, strict=True))
            and yaw <= _ANGLE_TOLERANCE_RAD
            and abs(self.pitch_rad - other.pitch_rad) <= _ANGLE_TOLERANCE_RAD
        )


def orbit_of(view: RvizView | None) -> OrbitCamera | None:
    """The Orbit view's camera (RViz's defaults for missing keys), or None for another view."""
    if view is None or not view.is_orbit:
        return None
    s = view.settings
    focal = s.get("Focal Point")
    focal = focal if isinstance(focal, Mapping) else {}
    try:
        return OrbitCamera(
            (float(focal.get("X", 0)), float(focal.get("Y", 0)), float(focal.get("Z", 0))),
            float(s.get("Distance", 10)),
            float(s.get("Yaw", 0.785398)),
            float(s.get("Pitch", 0.785398)),
        )
    except (TypeError, ValueError):
        return None


@dataclass(frozen=True, slots=True)
class ViewerState:
    """What the viewer shows that an RViz config holds outside its displays (camera None:
    robomodel's own); the displays are the Displays panel's (displays/attach.py)."""

    fixed_frame: str | None
    frame_rate_hz: float
    camera: OrbitCamera | None = None


def implied_state(document: RvizDocument, *, frame_rate_hz: float = 60.0) -> ViewerState:
    """What ``document`` makes the viewer show (``frame_rate_hz``: without a Frame Rate)."""
    s = document.settings
    return ViewerState(
        fixed_frame=s.fixed_frame,
        frame_rate_hz=s.frame_rate_hz or frame_rate_hz,
        camera=None if document.missing else orbit_of(document.config.view),
    )


def _with_view(config: RvizConfig, document: RvizDocument, camera: OrbitCamera) -> RvizConfig:
    view = config.view
    if view is None or not view.is_orbit:
        view = default_rviz_config(document.dialect).view
        assert view is not None  # RViz's default.rviz has one
    settings = dict(view.settings)
    x, y, z = camera.focal_point_m
    settings.update(
        {"Distance": camera.distance_m, "Focal Point": MappingProxyType({"X": x, "Y": y, "Z": z}),
         "Pitch": camera.pitch_rad, "Yaw": camera.yaw_rad}
    )  # fmt: skip
    return replace(config, view=RvizView(view.class_name, MappingProxyType(settings)))


def config_with_state(
    document: RvizDocument, state: ViewerState, *, frame_rate_hz: float = 60.0
) -> RvizConfig:
    """The document's config changed where ``state`` differs from what it implies
    (``frame_rate_hz``: the viewer's rate when the document has none)."""
    before = implied_state(document, frame_rate_hz=frame_rate_hz)
    config = document.config
    if state.fixed_frame != before.fixed_frame:
        config = replace(config, fixed_frame=state.fixed_frame)
    if state.frame_rate_hz != before.frame_rate_hz:
        config = replace(config, frame_rate_hz=state.frame_rate_hz)
    if state.camera is not None and not state.camera.close_to(before.camera):
        config = _with_view(config, document, state.camera)
    return config
