"""rviz, the rqt GUIs: their role is the launch's browser viewer.

``rviz -d file.rviz`` reads the config (Fixed Frame, Frame Rate, Background Color, RobotModel
and TF display options; other displays are named in the Status); a file that does not exist
yet is one warning, the viewer opens RViz's defaults and its Save Config writes the file, as
RViz does. ``rqt_robot_steering``,
``rqt_plot`` (topics from its arguments), ``rqt_gui`` and ``rqt_reconfigure`` open the viewer's
tool folders. One viewer serves every such node of the launch, as one screen would.
"""

from __future__ import annotations

from typing import Any

from robomodel.launch.nodes.base import NodeContext, RunningNode, plot_fields, register
from robomodel.launch.nodes.state import ViewerPart

__all__ = ["open_rviz_argument", "rviz_config_argument"]


def rviz_config_argument(args: tuple[str, ...]) -> str | None:
    """The file of ``-d FILE`` / ``--display-config FILE`` / ``-dFILE``."""
    for i, arg in enumerate(args):
        if arg in ("-d", "--display-config") and i + 1 < len(args):
            return args[i + 1]
        if arg.startswith("-d") and len(arg) > 2:
            return arg[2:]
        if arg.startswith("--display-config="):
            return arg.split("=", 1)[1]
    return None


def open_rviz_argument(ctx: NodeContext) -> Any:
    """The node's ``-d`` config as the viewer's RvizDocument (RViz's defaults, in the launch's
    ROS version, with one warning line, when the file does not exist; a file that exists but
    cannot be read is an error)."""
    from robomodel.viewer.rviz_document import open_rviz_document
    from robomodel.viewer.rviz_model import RvizDialect

    path = rviz_config_argument(ctx.spec.args)
    document, warning = open_rviz_document(path, RvizDialect(ctx.spec.dialect))
    if warning is not None:
        ctx.log(f"warning: {warning}")
    ctx.shared.rviz = document
    return document


@register("ros1", "rviz", "rviz", purpose="the browser viewer (RViz's RobotModel, TF, Grid)")
def rviz(ctx: NodeContext) -> RunningNode:
    request = ctx.viewer
    request.requested_by.append(ctx.spec.fqn)
    description = open_rviz_argument(ctx).settings.robot_description
    found = ctx.search(description)
    if found:
        request.robot_description_param = found
    return ViewerPart()


def _tools(ctx: NodeContext) -> RunningNode:
    """rqt tools (ROS 1 and 2): the viewer's tool folders; rqt_plot's fields, rqt_robot_steering's
    ``default_topic`` (a private parameter in ROS 1, a node parameter in ROS 2)."""
    request = ctx.viewer
    request.tools = True
    request.requested_by.append(ctx.spec.fqn)
    if ctx.spec.executable == "rqt_plot":
        request.plot_fields.extend(plot_fields(ctx.spec.args))
    if ctx.spec.executable == "rqt_robot_steering":
        if ctx.spec.dialect == "ros1":
            topic = ctx.param("~default_topic")
        else:
            topic = ctx.ros2_parameters("rqt_robot_steering").get("default_topic")
        if topic:
            request.steering_topic = str(topic)
    if ctx.spec.dialect == "ros1":
        found = ctx.search("robot_description")
        if found and request.robot_description_param is None:
            request.robot_description_param = found
    return ViewerPart()


for _package, _executable, _purpose in (
    ("rqt_robot_steering", "rqt_robot_steering", "the viewer's Robot Steering folder"),
    ("rqt_plot", "rqt_plot", "the viewer's Plot folder (topics from the arguments)"),
    ("rqt_gui", "rqt_gui", "the viewer's tool folders"),
    ("rqt_reconfigure", "rqt_reconfigure", "the viewer's Parameters folder"),
):
    for _dialect in ("ros1", "ros2"):
        register(_dialect, _package, _executable, purpose=_purpose)(_tools)
