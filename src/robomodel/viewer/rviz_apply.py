"""Apply an RViz configuration's settings to a running viewer's panel and scene."""

from __future__ import annotations

from typing import Any

import numpy as np

from robomodel.viewer.rviz_config import RvizSettings

__all__ = ["apply_rviz_settings"]


def apply_rviz_settings(viewer: Any, panel: Any, rviz: RvizSettings) -> None:
    """Global Options, RobotModel, TF and Grid settings, as RViz would start with them."""
    options = viewer.display_options
    if rviz.alpha is not None:
        options.alpha = rviz.alpha
        panel.alpha.value = rviz.alpha
    if rviz.visual_enabled is not None:
        options.show_visual = bool(rviz.visual_enabled) and rviz.robot_model_enabled
        panel.visual.value = options.show_visual
    elif not rviz.robot_model_enabled:
        options.show_visual = False
        panel.visual.value = False
    if rviz.collision_enabled is not None:
        options.show_collision = bool(rviz.collision_enabled) and rviz.robot_model_enabled
        panel.collision.value = options.show_collision
    tf = viewer.tf_display
    show_axes = rviz.tf_enabled and (rviz.tf_show_axes if rviz.tf_show_axes is not None else True)
    show_names = rviz.tf_enabled and bool(rviz.tf_show_names)
    tf.set_show_axes(bool(show_axes))
    panel.show_axes.value = bool(show_axes)
    tf.set_show_names(show_names)
    panel.show_names.value = show_names
    if rviz.tf_marker_scale is not None and rviz.tf_marker_scale > 0:
        tf.set_marker_scale(rviz.tf_marker_scale)
        panel.marker_scale.value = rviz.tf_marker_scale
    if rviz.grid_enabled is not None:
        panel.grid.visible = rviz.grid_enabled
        panel.show_grid.value = rviz.grid_enabled
    if rviz.background_rgb is not None and viewer.server is not None:
        image = np.empty((4, 4, 3), dtype=np.uint8)
        image[:] = rviz.background_rgb
        viewer.server.scene.set_background_image(image, format="png")
    if rviz.unsupported:
        viewer.status_note = (
            "\n\nRViz displays not drawn (robomodel has RobotModel, TF and Grid): "
            + ", ".join(rviz.unsupported)
        )
