"""The page's option folders: Status, Global Options (Fixed Frame, Frame Rate), and RobotModel
and TF in the Displays folder.

Property names are RViz's (Visual Enabled, Collision Enabled, Alpha, Show Axes, Show Names,
Marker Scale), so that a user of RViz finds them where expected. Changes are posted to the
viewer's loop thread, which owns the displays.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from robomodel.viewer.scene import RobotModelDisplay
from robomodel.viewer.session import DisplayOptions
from robomodel.viewer.tf_display import TFDisplay

__all__ = ["OptionsPanel"]


class OptionsPanel:
    """Builds the option folders and the grid, and wires them to the displays.

    Args:
        server: The viser server.
        fixed_frame: Initial Fixed Frame.
        options: RobotModel options shared with displays built later (updated in place).
        post: Runs a callable on the viewer's loop thread.
        displays: The current RobotModel displays (asked at each change).
        on_fixed_frame: Called (on the loop thread) with a newly chosen Fixed Frame.
    """

    def __init__(
        self,
        server: Any,
        *,
        fixed_frame: str,
        options: DisplayOptions,
        post: Callable[[Callable[[], None]], None],
        displays: Callable[[], Sequence[RobotModelDisplay]],
        on_fixed_frame: Callable[[str], None],
        frame_rate_hz: float = 60.0,
        on_frame_rate: Callable[[float], None] = lambda _hz: None,
    ) -> None:
        gui = server.gui
        gui.configure_theme(control_width="large")  # room for file:line errors and mesh paths
        server.scene.set_up_direction("+z")
        with gui.add_folder("Status"):
            self.status = gui.add_markdown("loading...")
        with gui.add_folder("Global Options"):
            self.fixed_dropdown = gui.add_dropdown(
                "Fixed Frame", (fixed_frame,), initial_value=fixed_frame
            )
            self.frame_rate = frame_rate = gui.add_number(
                "Frame Rate", frame_rate_hz, min=1.0, max=1000.0, step=1.0
            )
        self.tf_display = TFDisplay(server.scene)
        # RViz's Displays tree: RobotModel and TF first, the Displays panel adds the others.
        self.displays_folder = gui.add_folder("Displays")
        with self.displays_folder, gui.add_folder("RobotModel"):
            visual = gui.add_checkbox("Visual Enabled", options.show_visual)
            collision = gui.add_checkbox("Collision Enabled", options.show_collision)
            alpha = gui.add_slider(
                "Alpha", min=0.0, max=1.0, step=0.01, initial_value=options.alpha
            )
        with self.displays_folder, gui.add_folder("TF", expand_by_default=False):
            axes = gui.add_checkbox("Show Axes", True)
            names = gui.add_checkbox("Show Names", False)
            scale = gui.add_number("Marker Scale", 1.0, min=0.01, max=100.0, step=0.1)
        # Kept so that an RViz config (-d file.rviz) can set them after start.
        self.visual, self.collision, self.alpha = visual, collision, alpha
        self.show_axes, self.show_names, self.marker_scale = axes, names, scale

        def each(action: Callable[[RobotModelDisplay], None]) -> Callable[[], None]:
            def run() -> None:
                for display in displays():
                    action(display)

            return run

        def on_fixed(_event: Any) -> None:
            frame = str(self.fixed_dropdown.value)
            post(lambda: on_fixed_frame(frame))

        def on_visual(_event: Any) -> None:
            options.show_visual = bool(visual.value)
            post(each(lambda d: d.set_visual_enabled(options.show_visual)))

        def on_collision(_event: Any) -> None:
            options.show_collision = bool(collision.value)
            post(each(lambda d: d.set_collision_enabled(options.show_collision)))

        def on_alpha(_event: Any) -> None:
            options.alpha = float(alpha.value)
            post(each(lambda d: d.set_alpha(options.alpha)))

        def on_frame_rate_changed(_event: Any) -> None:
            hz = float(frame_rate.value)
            if hz > 0:
                post(lambda: on_frame_rate(hz))

        tf = self.tf_display
        self.fixed_dropdown.on_update(on_fixed)
        frame_rate.on_update(on_frame_rate_changed)
        visual.on_update(on_visual)
        collision.on_update(on_collision)
        alpha.on_update(on_alpha)
        axes.on_update(lambda _e: post(lambda: tf.set_show_axes(bool(axes.value))))
        names.on_update(lambda _e: post(lambda: tf.set_show_names(bool(names.value))))
        scale.on_update(lambda _e: post(lambda: tf.set_marker_scale(float(scale.value))))
