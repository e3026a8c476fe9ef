"""The course robots as the tutorials show them: each drawn, then kept for the documentation.

`make docs` copies build/viewer-screenshots/ into the site, so the tutorials' pictures are what
these tests saw (tools/docs_screenshots.py runs the tests of any screenshot that is missing).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from tests.conftest import EXAMPLES
from tests.viewer.conftest import (
    ViewerProcess,
    changed_view,
    open_viewer,
    save_shot,
    settle,
    slider_input,
    toggle_checkbox,
    wait_for,
)

pytestmark = pytest.mark.browser


def _assert_drawn(page: Any) -> None:
    """The robot covers pixels that hidden visuals leave as background."""

    # the robot's meshes may reach the page after the sliders: wait until the Status no longer
    # says "loading" (its first text, then "loading N mesh(es)..." until they are drawn; the
    # TF display's axes alone are "something drawn")
    wait_for(lambda: page.locator("text=loading").count() == 0, what="the meshes loaded")

    def something_drawn() -> Any:
        image = settle(page)
        return (image,) if (image < 200).any() else None

    (drawn,) = wait_for(something_drawn, what="the robot drawn")
    toggle_checkbox(page, "Visual Enabled")
    changed_view(page, drawn, 0.0005, what="the visuals hidden")  # the arm is small in view
    toggle_checkbox(page, "Visual Enabled")
    settle(page)  # drawn again before the picture is taken


def test_planar_3dof_with_its_sliders(viewer: Callable[..., ViewerProcess], page: Any) -> None:
    view = viewer(EXAMPLES / "gripper_description/urdf/planar_3dof.urdf")
    open_viewer(page, view.url)
    for joint in ("joint_1", "joint_2", "joint_3"):
        page.get_by_text(joint, exact=True).first.wait_for()
    box = slider_input(page, "joint_2")
    box.fill("0.8")
    box.press("Enter")
    wait_for(lambda: abs(float(box.input_value()) - 0.8) < 1e-6, what="joint_2 at 0.8")
    _assert_drawn(page)
    save_shot(page, "planar_3dof")


def test_planar_3dof_xacro_with_its_sliders(
    viewer: Callable[..., ViewerProcess], page: Any
) -> None:
    view = viewer(EXAMPLES / "gripper_description/urdf/planar_3dof.xacro")
    open_viewer(page, view.url)
    page.get_by_text("joint_3", exact=True).first.wait_for()
    _assert_drawn(page)
    save_shot(page, "planar_3dof_xacro")


def test_ur5(viewer: Callable[..., ViewerProcess], page: Any) -> None:
    view = viewer(
        EXAMPLES / "ur5_description/urdf/ur5_robot.urdf.xacro",
        "--package-path",
        EXAMPLES,
    )
    open_viewer(page, view.url)
    page.get_by_text("shoulder_lift_joint", exact=True).first.wait_for()
    _assert_drawn(page)
    save_shot(page, "ur5")


def test_two_link_arm_xacro(viewer: Callable[..., ViewerProcess], page: Any) -> None:
    view = viewer(EXAMPLES / "two_link_arm/urdf/two_link_arm.urdf.xacro")
    open_viewer(page, view.url)
    for joint in ("joint1", "joint2", "joint3"):  # the xacro's recursion makes three links
        page.get_by_text(joint, exact=True).first.wait_for()
    box = slider_input(page, "joint2")
    box.fill("0.9")
    box.press("Enter")
    wait_for(lambda: abs(float(box.input_value()) - 0.9) < 1e-6, what="joint2 at 0.9")
    _assert_drawn(page)
    save_shot(page, "two_link_arm")
