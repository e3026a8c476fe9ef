"""The viewer's empty start and seed 004's two namespaced robots in headless Chromium: the page
of example_description's two_robots.rviz shows the Grid and no robot until the robots'
robot_state_publishers publish, then both robots where TF puts them."""

from __future__ import annotations

from typing import Any

import pytest

from robomodel.viewer import Viewer
from tests.viewer.conftest import changed_fraction, open_viewer, save_shot, settle, wait_for
from tests.viewer.test_empty_start import _empty_viewer, _start_namespaced_robots
from tests.viewer.test_tools_inprocess import on_loop

pytestmark = pytest.mark.browser
empty_viewer = _empty_viewer  # the fixture, under its name


def test_the_page_starts_empty_and_shows_both_namespaced_robots(empty_viewer: Viewer, page: Any) -> None:  # fmt: skip
    viewer = empty_viewer
    open_viewer(page, viewer.url)
    page.get_by_text("RobotModel robot1", exact=True).first.click()  # its folder: the status
    page.get_by_text("Waiting for the robot description on [/robot1/robot_description]").first.wait_for()  # fmt: skip
    empty = settle(page)
    save_shot(page, "empty_start")
    kept = on_loop(viewer, lambda: _start_namespaced_robots(viewer))
    assert kept
    wait_for(lambda: viewer.status.content == "OK", what="both robots placed")
    wait_for(lambda: changed_fraction(empty, settle(page, 2)) > 0.01, what="the robots drawn")
    save_shot(page, "two_robots_rviz")
