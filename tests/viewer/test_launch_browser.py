"""The display launch in a real browser: ``robomodel launch gripper_description
display_xacro.launch`` (xacro command, ``use_gui``, state_publisher, ``rviz -d urdf.rviz``)
serves the viewer with the .rviz file's settings, and its sliders move the robot for every
process on the bus."""

from __future__ import annotations

import os
import subprocess
from typing import Any

import pytest
import yaml

from tests.conftest import EXAMPLES, ROBOMODEL
from tests.timing import scaled
from tests.viewer.conftest import (
    changed_fraction,
    domain_id,
    gui_row,
    open_viewer,
    save_shot,
    screenshot,
    slider_input,
    start_launch_viewer,
    wait_for,
)

pytest.importorskip("viser")
pytest.importorskip("zenoh")


def _joint_states(domain: str) -> dict[str, float]:
    echo = subprocess.run(
        [*ROBOMODEL, "topic", "echo", "/joint_states", "--once", "--domain-id", domain],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip
    assert echo.returncode == 0, echo.stderr
    msg = yaml.safe_load(echo.stdout.split("---")[0])
    return dict(zip(msg["name"], msg["position"], strict=True))


def _scene(page: Any) -> Any:
    """Everything left of the panel and below the notification corner: this small arm is
    drawn right of the centre, beyond the tests' usual scene region."""
    image = screenshot(page)
    h, w, _ = image.shape
    return image[int(0.2 * h) :, : int(0.68 * w)]


def test_display_launch_sliders_move_the_robot(page: Any) -> None:
    domain = domain_id()
    env = {**os.environ, "ROS_PACKAGE_PATH": str(EXAMPLES)}
    launch, url, _lines = start_launch_viewer(
        "gripper_description", "display_xacro.launch", domain=domain, env=env
    )
    try:
        open_viewer(page, url)
        # urdf.rviz's Global Options reached the page
        fixed = gui_row(page, "Fixed Frame").locator("input:not([type=hidden])").first
        wait_for(lambda: fixed.input_value() == "base_link", what="Fixed Frame from urdf.rviz")
        wait_for(lambda: "gripper" in page.content(), what="the TF frame names drawn")
        before = _scene(page)
        box = slider_input(page, "joint_2")
        box.fill("1.2")
        box.press("Enter")
        wait_for(
            lambda: abs(_joint_states(domain).get("joint_2", 0.0) - 1.2) < 1e-6,
            timeout_s=30,
            what="joint_2 = 1.2 on /joint_states from the slider",
        )
        wait_for(
            lambda: changed_fraction(before, _scene(page)) > 0.002,
            timeout_s=30,
            what="the arm to move in the page",
        )
        save_shot(page, "launch_display_xacro_slider")
        # robot_state_publisher (state_publisher) follows the sliders: another process sees it
        tf = subprocess.run(
            [*ROBOMODEL, "tf", "link_1", "link_2", "--once", "--timeout", f"{scaled(20):.1f}",
             "--domain-id", domain],
            capture_output=True, text=True, timeout=scaled(60),
        )  # fmt: skip
        assert tf.returncode == 0 and "Translation" in tf.stdout, tf.stderr
        assert launch.poll() is None
    finally:
        launch.terminate()
        launch.wait(timeout=scaled(30))
