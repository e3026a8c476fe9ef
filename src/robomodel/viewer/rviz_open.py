"""RViz's File > Open Config on a running viewer: everything the file holds, applied again.

Global Options (Fixed Frame, Frame Rate, background) as
:func:`~robomodel.viewer.rviz_apply.apply_rviz_document` applies them at start, the Displays
panel emptied and filled with the file's displays (RobotModel and TF among them), and the file's Orbit view on every page
(RViz's ``VisualizationFrame::loadDisplayConfig`` replaces all of it likewise).
"""

from __future__ import annotations

import logging
from typing import Any

from robomodel.viewer.displays.attach import open_config_displays
from robomodel.viewer.markup import Markup
from robomodel.viewer.rviz_apply import apply_rviz_document, apply_rviz_view
from robomodel.viewer.rviz_document import RvizDocument

__all__ = ["reopen_rviz_document"]

log = logging.getLogger("robomodel.viewer")


def reopen_rviz_document(viewer: Any, panel: Any, document: RvizDocument) -> None:
    """Apply ``document`` to the running ``viewer`` (loop thread: it owns the displays)."""
    viewer.status_note = Markup("")
    apply_rviz_document(viewer, panel, document)
    frame = document.settings.fixed_frame
    if frame:
        viewer.fixed_frame = frame
        dropdown = panel.fixed_dropdown
        dropdown.options = tuple(sorted({*dropdown.options, frame}))
        dropdown.value = frame
    displays = viewer.displays_panel
    if displays is not None:
        if displays.follower is not None:  # the file says what to show, as in RViz
            displays.follower.stop()
        for row in list(displays.rows):
            displays.remove(row)
        for problem in open_config_displays(displays, document, viewer.sessions):
            log.warning("RViz config %s: %s", document.path, problem)
    apply_rviz_view(viewer.server, document)
    camera = viewer.server.initial_camera
    for client in viewer.server.get_clients().values():
        client.camera.look_at = camera.look_at
        client.camera.position = camera.position
