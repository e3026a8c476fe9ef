"""The launch's GUI works from what it is given (options, the viewer request, what the nodes
share, the bus): no runner is needed to start or close it."""

from __future__ import annotations

from robomodel.launch.gui import GuiOptions, LaunchGui
from robomodel.launch.nodes.base import LaunchShared, ViewerRequest
from robomodel.runtime import Context

URDF = """<robot name="arm">
  <link name="base"/><link name="tip"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="tip"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


def _publishers(context: Context, topic: str) -> set[str]:
    info = context.graph().topics.get(topic)
    return set() if info is None else {e.node for e in info.publishers}


def test_headless_sliders_stand_in_until_the_gui_closes() -> None:
    context = Context("inproc")
    try:
        request = ViewerRequest(sliders=True, requested_by=["joint_state_publisher_gui"])
        robot = request.robot("/r1")
        robot.description_text = URDF
        robot.joint_states_topic = "/r1/joint_states"
        lines: list[str] = []
        gui = LaunchGui(
            GuiOptions(headless=True),
            request,
            LaunchShared(),
            context=context,
            params=None,
            log=lines.append,
        )
        gui.start()
        assert _publishers(context, "/r1/joint_states") == {"/r1/joint_state_publisher_gui"}
        assert any("headless" in line for line in lines)
        gui.close()
        assert _publishers(context, "/r1/joint_states") == set()
    finally:
        context.shutdown()


def test_a_robot_without_a_description_is_reported_not_drawn() -> None:
    context = Context("inproc")
    try:
        request = ViewerRequest(sliders=True, requested_by=["joint_state_publisher_gui"])
        request.robot("/r2").description_param = "/r2/robot_description"
        lines: list[str] = []
        gui = LaunchGui(
            GuiOptions(headless=True), request, LaunchShared(), context=context, params=None,
            log=lines.append,
        )  # fmt: skip
        gui.start()
        assert lines == ["[launch] the viewer has no robot to show in /r2"]
        assert _publishers(context, "/r2/joint_states") == set()
        gui.close()
    finally:
        context.shutdown()
