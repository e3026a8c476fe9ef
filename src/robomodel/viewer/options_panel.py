"""The page's option folders: Status, Global Options (Fixed Frame, Frame Rate), and the
Displays folder, which the Displays panel fills (RobotModel, TF and every other display).

Changes are posted to the viewer's loop thread, which owns the displays.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from robomodel.viewer.markup import safe_markdown

__all__ = ["OptionsPanel"]


class OptionsPanel:
    """Builds the option folders and wires them to the viewer.

    Args:
        server: The viser server.
        fixed_frame: Initial Fixed Frame.
        post: Runs a callable on the viewer's loop thread.
        on_fixed_frame: Called (on the loop thread) with a newly chosen Fixed Frame.
        frame_rate_hz: Initial Frame Rate.
        on_frame_rate: Called (on the loop thread) with a new Frame Rate.
    """

    def __init__(
        self,
        server: Any,
        *,
        fixed_frame: str,
        post: Callable[[Callable[[], None]], None],
        on_fixed_frame: Callable[[str], None],
        frame_rate_hz: float = 60.0,
        on_frame_rate: Callable[[float], None] = lambda _hz: None,
    ) -> None:
        gui = server.gui
        gui.configure_theme(control_width="large")  # room for file:line errors and mesh paths
        server.scene.set_up_direction("+z")
        with gui.add_folder("Status"):
            self.status = safe_markdown(gui, "loading...")
        with gui.add_folder("Global Options"):
            self.fixed_dropdown = gui.add_dropdown(
                "Fixed Frame", (fixed_frame,), initial_value=fixed_frame
            )
            self.frame_rate = frame_rate = gui.add_number(
                "Frame Rate", frame_rate_hz, min=1.0, max=1000.0, step=1.0
            )
        # RViz's Displays tree: the Displays panel adds RobotModel, TF and the others here.
        self.displays_folder = gui.add_folder("Displays")

        def on_fixed(_event: Any) -> None:
            frame = str(self.fixed_dropdown.value)
            post(lambda: on_fixed_frame(frame))

        def on_frame_rate_changed(_event: Any) -> None:
            hz = float(frame_rate.value)
            if hz > 0:
                post(lambda: on_frame_rate(hz))

        self.fixed_dropdown.on_update(on_fixed)
        frame_rate.on_update(on_frame_rate_changed)
