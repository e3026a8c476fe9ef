"""In a real browser: a config's text reaches the page as text, never as HTML that runs.

viser renders markdown with raw HTML, so before every markdown element went through
``robomodel.viewer.markup``, a display class named ``<iframe srcdoc="<script>...">`` in a
``.rviz`` ran script in the viewer's origin when its name was quoted in the Status panel.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.conftest import EXAMPLES
from tests.viewer.conftest import ViewerProcess, open_viewer, wait_for

pytest.importorskip("viser")

PAYLOAD = "<iframe srcdoc=\"<script>parent.document.title='PWNED'</script>\"></iframe>"


def test_a_hostile_display_class_is_shown_as_text_and_runs_nothing(
    viewer: Callable[..., ViewerProcess], page: Any, tmp_path: Path
) -> None:
    config = tmp_path / "hostile.rviz"
    display = {"Class": PAYLOAD, "Name": "x", "Enabled": True}
    config.write_text(yaml.safe_dump({"Visualization Manager": {"Displays": [display]}}))
    view = viewer(
        EXAMPLES / "gripper_description/urdf/planar_3dof.urdf", "-d", str(config), cwd=tmp_path
    )
    open_viewer(page, view.url)
    title = page.evaluate("document.title")
    wait_for(lambda: "RViz displays not drawn" in page.inner_text("body"), what="the Status note")
    assert "<iframe srcdoc=" in page.inner_text("body")  # shown as written
    assert page.locator("iframe").count() == 0
    assert page.evaluate("document.title") == title != "PWNED"
