"""An RViz config on a running viewer's panel and scene, and the panel read back as one."""

from __future__ import annotations

from typing import Any

import numpy as np

from robomodel.viewer.displays.base import display_classes
from robomodel.viewer.markup import md
from robomodel.viewer.rviz_document import RvizDocument
from robomodel.viewer.rviz_state import OrbitCamera, ViewerState, implied_state

__all__ = ["apply_rviz_document", "apply_rviz_view", "viewer_state"]


def apply_rviz_document(viewer: Any, panel: Any, document: RvizDocument) -> None:
    """Global Options (Frame Rate, background) as RViz would start with them; the displays,
    RobotModel and TF among them, are the Displays panel's (displays/attach.py)."""
    state = implied_state(document, frame_rate_hz=viewer.frame_rate_hz)
    viewer.frame_rate_hz = panel.frame_rate.value = state.frame_rate_hz
    rviz = document.settings
    # A file that does not exist yet keeps robomodel's background; the defaults' (RViz's dark
    # grey) is what the saved file holds and RViz shows.
    if rviz.background_rgb is not None and viewer.server is not None and not document.missing:
        image = np.empty((4, 4, 3), dtype=np.uint8)
        image[:] = rviz.background_rgb
        viewer.server.scene.set_background_image(image, format="png")
    if rviz.unsupported:
        have = ", ".join(display_classes())
        viewer.status_note = md(
            "\n\nRViz displays not drawn (robomodel has {}): {}", have, ", ".join(rviz.unsupported)
        )


def apply_rviz_view(server: Any, document: RvizDocument) -> None:
    """The config's Orbit view as the page's initial camera (robomodel's own when the file
    did not exist or its view is not an Orbit)."""
    camera = implied_state(document).camera
    if camera is not None:
        server.initial_camera.look_at = camera.focal_point_m
        server.initial_camera.position = camera.position_m()


def viewer_state(panel: Any, camera: Any | None) -> ViewerState:
    """What the page shows now (``camera``: a browser's, with ``position`` and ``look_at``).

    GUI values are read from the controls, not from the loop's copies, so that a change made
    just before Save Config is saved even if the loop has not applied it yet.
    """
    return ViewerState(
        fixed_frame=str(panel.fixed_dropdown.value),
        frame_rate_hz=float(panel.frame_rate.value),
        camera=OrbitCamera.looking(camera.position, camera.look_at) if camera else None,
    )
