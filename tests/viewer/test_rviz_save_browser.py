"""RViz configs in a real browser: seed 000's display.launch before urdf.rviz exists serves the
viewer with Grid, RobotModel and TF; the student sets the Fixed Frame and clicks Save Config,
and the file is RViz's; Save Config As asks for a path and writes there."""

from __future__ import annotations

import os
import shutil
from pathlib import Path
from typing import Any

import pytest

from robomodel.viewer.rviz_config import read_rviz_file
from tests.conftest import EXAMPLES
from tests.timing import scaled
from tests.viewer.conftest import (
    domain_id,
    gui_row,
    open_viewer,
    save_shot,
    start_launch_viewer,
    wait_for,
)

pytest.importorskip("viser")
pytest.importorskip("zenoh")


def _checked(page: Any, label: str) -> bool:
    return bool(gui_row(page, label).locator("input[type=checkbox]").first.is_checked())


def test_save_config_writes_the_missing_rviz_file_of_display_launch(
    page: Any, tmp_path: Path
) -> None:
    package = tmp_path / "gripper_description"
    shutil.copytree(EXAMPLES / "gripper_description", package)
    config = package / "urdf/urdf.rviz"
    config.unlink()
    env = {**os.environ, "ROS_PACKAGE_PATH": str(tmp_path)}
    launch, url, lines = start_launch_viewer(
        "gripper_description", "display.launch", domain=domain_id(), env=env
    )
    try:
        warnings = [x for x in lines if "urdf.rviz" in x and "does not exist" in x]
        assert len(warnings) == 1, "".join(lines)
        open_viewer(page, url)
        wait_for(lambda: "does not exist yet" in page.content(), what="the File folder's note")
        page.get_by_text("Grid", exact=True).first.wait_for()  # RViz's default Grid display
        page.get_by_text("TF", exact=True).filter(
            visible=True
        ).click()  # not the type list's  # the TF folder (collapsed)
        wait_for(lambda: _checked(page, "Show Axes"), what="TF's Show Axes")
        assert _checked(page, "Visual Enabled")  # RobotModel
        page.locator("input[value='base_link']:not([type=hidden])").click()
        page.get_by_role("option", name="link_1", exact=True).click()
        page.get_by_role("button", name="Save Config", exact=True).click()
        wait_for(config.exists, what=f"{config} written")
        wait_for(lambda: "Saved RViz config" in page.content(), what="the saved note")
        save_shot(page, "rviz_save_config")
        saved = read_rviz_file(config)
        assert saved.fixed_frame == "link_1"
        assert [(d.class_name, d.enabled) for d in saved.displays] == [
            ("rviz/Grid", True), ("rviz/RobotModel", True), ("rviz/TF", True),
        ]  # fmt: skip
        assert saved.view is not None and saved.view.class_name == "rviz/Orbit"
        text = config.read_text()
        assert text.startswith("Panels:\n") and '  Class: ""\n' in text
        # Save Config As: a dialog asks for the path; later saves go there.
        other = config.parent / "copy" / "view_urdf.rviz"  # a page saves beside the -d file
        page.get_by_role("button", name="Save Config As", exact=True).click()
        box = gui_row(page, "Path").locator("input:not([type=hidden])").first
        box.wait_for(timeout=scaled(20) * 1000)  # playwright's timeouts are in ms
        box.fill(str(other))
        page.get_by_role("button", name="Save", exact=True).click()
        wait_for(other.exists, what=f"{other} written")
        assert read_rviz_file(other).fixed_frame == "link_1"
        assert launch.poll() is None
    finally:
        launch.terminate()
        launch.wait(timeout=scaled(30))
