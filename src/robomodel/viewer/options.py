"""What ``robomodel view`` takes from its command line (and launch's ``rviz2`` / ``gzclient``)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from robomodel.description.packages import PackageIndex
from robomodel.viewer.rviz_document import RvizDocument
from robomodel.viewer.scenery import SceneryShape
from robomodel.viewer.session import RobotSource

__all__ = ["ViewerOptions"]


@dataclass(frozen=True, slots=True)
class ViewerOptions:
    """Everything ``robomodel view`` takes from its command line.

    Args:
        sources: The robots, in command-line order.
        host, port: Where to serve the page (loopback by default).
        fixed_frame: RViz's Fixed Frame; default the first robot's root link.
        bus: ``"inproc"``, ``"zenoh"`` or ``"ros1"`` (``master``: the ROS 1 master's URI,
            default ``ROS_MASTER_URI``).
        external: Joint states (or /tf) come from another process on the bus.
        state_publisher: With ``external``, run a robot_state_publisher per robot (turning
            /joint_states from the bus into /tf); off when that process runs its own.
        reload_period_s: How often the description files are polled for changes.
        tools: Show the rqt tools (steering, plot, publisher, parameters); without a config,
            also add displays for the graph's scans and odometry (displays/follow.py).
        scenery: Shapes that belong to no robot, drawn in their TF frames (a world's walls).
        scenery_source: For scenery that changes while the viewer runs (a simulator's world
            gaining or losing models, as gzclient shows ``spawn_model -sdf``): called a few
            times a second, on the viewer's loop; when it returns other shapes than those
            drawn, they replace them. ``scenery`` is what is drawn until the first call.
        frame_rate_hz: At most this many scene updates per second (RViz's Global Options >
            Frame Rate). Default 60: a browser draws 60 frames a second, more updates are never
            seen. TF arriving faster (a simulation publishes at 100 Hz and more, a dragged slider
            at the GUI's event rate) is merged into the next update, so a slow browser is never
            flooded.
        rviz: The RViz config (``-d file.rviz``, or RViz's defaults when that file does not
            exist yet): applied after start; Save Config writes it.
    """

    sources: tuple[RobotSource, ...]
    host: str = "127.0.0.1"
    port: int = 8080
    fixed_frame: str | None = None
    bus: str = "inproc"
    master: str | None = None
    domain_id: int | None = None
    connect: tuple[str, ...] = ()
    listen: tuple[str, ...] = ()
    external: bool = False
    state_publisher: bool = True
    package_index: PackageIndex = field(default_factory=PackageIndex)
    reload_period_s: float = 0.25
    tools: bool = True
    scenery: tuple[SceneryShape, ...] = ()
    scenery_source: Callable[[], tuple[SceneryShape, ...]] | None = None
    frame_rate_hz: float = 60.0
    rviz: RvizDocument | None = None
