"""The in-process viewer of the planar arm that the RobotModel tests add other robots beside
(test_robot_model_topics, test_robot_model_files): import ``planar_viewer`` into the test
module and ask for the ``viewer`` fixture."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from tests.conftest import EXAMPLES

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"


@pytest.fixture(name="viewer")
def planar_viewer() -> Iterator[Viewer]:
    """A started viewer of :data:`PLANAR` on any free port, checking its files every 0.05 s."""
    viewer = Viewer(
        ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, reload_period_s=0.05)
    )
    viewer.start()
    yield viewer
    viewer.close()
