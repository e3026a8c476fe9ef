"""The viewer starts with no robot, as RViz does, and a RobotModel display brings each robot:
seed 004's two namespaced robots (robot_state_publisher in ``/robot1`` and ``/robot2`` with
``frame_prefix`` ``robot1/`` and ``robot2/``) from one RViz 2 config with a RobotModel per
robot (its Description Topic and TF Prefix), saved back as it was read."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from robomodel.description.packages import PackageIndex
from robomodel.loading import read_description
from robomodel.runtime.msg import TFMessage
from robomodel.runtime.nodes.joint_state_publisher import JointStatePublisher
from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher
from robomodel.runtime.qos import latched
from robomodel.viewer import Viewer, ViewerOptions
from robomodel.viewer.displays.base import StatusLevel
from robomodel.viewer.rviz_document import open_rviz_document
from robomodel.viewer.rviz_model import RvizDialect
from tests.conftest import EXAMPLES
from tests.viewer.conftest import wait_for
from tests.viewer.test_robot_model_topics import _static
from tests.viewer.test_tools_inprocess import on_loop

PACKAGE = EXAMPLES / "example_description"
CONFIG = PACKAGE / "config/two_robots.rviz"


@pytest.fixture(name="empty_viewer")
def _empty_viewer() -> Iterator[Viewer]:
    document, warning = open_rviz_document(str(CONFIG), RvizDialect.ROS2)
    assert warning is None
    viewer = Viewer(ViewerOptions(sources=(), port=0, rviz=document, tools=False))
    viewer.start()
    yield viewer
    viewer.close()


def _root_xyz(viewer: Viewer, prefix: str) -> np.ndarray | None:
    """Where the page draws the root link of the robot whose frames have ``prefix``."""

    def read() -> np.ndarray | None:
        session = next((s for s in viewer.sessions if s.frame_prefix == prefix), None)
        if session is None or session.display is None or session.robot is None:
            return None
        drawing = session.display
        handle = drawing._links[drawing.link_names.index(session.robot.tree().root)]
        return np.array(handle.position) if handle.visible else None

    return on_loop(viewer, read)  # type: ignore[no-any-return]


def _start_namespaced_robots(viewer: Viewer) -> list[object]:
    """What ``namespaced.launch.py namespace:=robot1`` (and robot2) and two_robots.launch.py's
    static transforms run: robot2 one metre to the left of robot1 in ``world``."""
    assert viewer.context is not None
    index = PackageIndex(packages={"example_description": PACKAGE})
    result, _ = read_description(str(PACKAGE / "urdf/example.urdf.xacro"), package_index=index)
    context = viewer.context
    node = context.create_node("world_statics")
    statics = node.create_publisher(TFMessage, "/tf_static", latched(10))
    statics.publish(TFMessage([_static("world", "robot1/base_footprint", (0.0, 0.0, 0.0)),
                               _static("world", "robot2/base_footprint", (0.0, 1.0, 0.0))]))  # fmt: skip
    kept: list[object] = [node, statics]
    for name in ("robot1", "robot2"):
        kept.append(RobotStatePublisher(context, result.robot, namespace=f"/{name}",
                                        parameters={"frame_prefix": f"{name}/"}))  # fmt: skip
        sliders = JointStatePublisher(context, result.robot, namespace=f"/{name}")
        sliders.publish()
        kept.append(sliders)
    return kept


def test_two_namespaced_robots_come_from_the_config_s_robot_models(
    empty_viewer: Viewer, tmp_path: Path
) -> None:
    viewer = empty_viewer
    models = {d.name: d for d in viewer.displays.displays if d.class_name == "RobotModel"}
    assert sorted(models) == ["RobotModel robot1", "RobotModel robot2"]
    wait_for(lambda: all(m.status.text.startswith("Waiting for the robot description on [/robot")
                         for m in models.values()), what="both waiting, no robot drawn")  # fmt: skip
    assert all(s.robot is None for s in viewer.sessions)
    kept = on_loop(viewer, lambda: _start_namespaced_robots(viewer))
    assert kept
    for name, left_m in (("robot1", 0.0), ("robot2", 1.0)):
        model = models[f"RobotModel {name}"]
        wait_for(lambda m=model, n=name: m.status.text == f"Showing {n}/example",  # type: ignore[misc]
                 what=f"{name} shown")  # fmt: skip
        assert model.status.level is StatusLevel.OK
        # its links are looked up at <TF Prefix>/<link>: where world's static put its root
        wait_for(lambda n=name, y=left_m: (p := _root_xyz(viewer, f"{n}/")) is not None  # type: ignore[misc]
                 and np.allclose(p, (0.0, y, 0.0), atol=1e-6), what=f"{name} drawn at y={left_m}")  # fmt: skip
    wait_for(lambda: viewer.status.content == "OK", what="the status to clear")
    # Save Config writes the RobotModels' Description Source, Topic and TF Prefix as read
    out = tmp_path / "saved.rviz"
    assert viewer.config_panel.save(str(out))
    saved, _ = open_rviz_document(str(out), RvizDialect.ROS2)
    read, _ = open_rviz_document(str(CONFIG), RvizDialect.ROS2)
    keys = ("Description Source", "Description Topic", "TF Prefix")

    def models_of(document: object) -> list[tuple[object, ...]]:
        displays = document.config.displays  # type: ignore[attr-defined]
        return [tuple(d.settings.get(k) for k in keys) for d in displays if d.kind == "RobotModel"]

    assert models_of(saved) == models_of(read)
    assert [m[2] for m in models_of(saved)] == ["robot1", "robot2"]
    assert saved.settings.fixed_frame == "world"


def test_run_rviz2_without_a_robot_description_serves_an_empty_viewer() -> None:
    """``robomodel run rviz2 rviz2`` while nobody publishes /robot_description: RViz 2 opens
    with no robot, and so does the viewer (its RobotModel waits for the description)."""
    import signal
    import subprocess
    import time

    from tests.conftest import ROBOMODEL, unique_domain
    from tests.timing import scaled

    rviz = subprocess.Popen(
        [*ROBOMODEL, "run", "--no-browser", "--port", "0", "--bus", "zenoh",
         "--domain-id", unique_domain(), "rviz2", "rviz2"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
    )  # fmt: skip
    seen: list[str] = []
    try:
        assert rviz.stdout is not None
        deadline = time.monotonic() + scaled(60)
        while time.monotonic() < deadline and not any("viewer: serving" in s for s in seen):
            line = rviz.stdout.readline()
            if not line:
                break
            seen.append(line)
        text = "".join(seen)
        assert "viewer: serving http://" in text, text
        assert "/robot_description is not set: the viewer starts with no robot" in text, text
    finally:
        rviz.send_signal(signal.SIGINT)
        rviz.wait(scaled(20))
