"""One robot in the viewer: its description, its publishers, its display and its controls.

A session loads (and on change reloads) one description file, runs robot_state_publisher and,
unless joint states come from the bus, joint_state_publisher for it, and keeps the
RobotModel display and the joint panel in step with the last description that loaded.
A description that fails to load leaves the last good model in place and records the error.
"""

from __future__ import annotations

import posixpath
import threading
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.description.model import JointType, Robot
from robomodel.description.packages import PackageIndex
from robomodel.description.urdf.writer import urdf_to_string
from robomodel.errors import RobomodelError
from robomodel.loading import LoadedDescription, read_description
from robomodel.runtime.context import Context
from robomodel.runtime.msg import TFMessage
from robomodel.runtime.node import Node
from robomodel.runtime.nodes.joint_state_publisher import JointStatePublisher
from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher
from robomodel.tf import BufferCore
from robomodel.viewer.displays.robot_model import LinkUpdates
from robomodel.viewer.joint_panel import BodyPose, JointPanel
from robomodel.viewer.link_poses import LinkPoses, LinkPoseSolver
from robomodel.viewer.meshes import MeshCache
from robomodel.viewer.reload import FileWatcher, TopicWatcher
from robomodel.viewer.robot_source import DisplayOptions, LoadFailure, RobotSource
from robomodel.viewer.scene import RobotModelDisplay
from robomodel.viewer.session_controls import JointControls

__all__ = ["DisplayOptions", "LoadFailure", "RobotSession", "RobotSource"]


class RobotSession(JointControls):
    """Loads, publishes, draws and controls one robot.

    Args:
        number: Position on the command line (0-based); names scene nodes and namespaces.
        source: The file, xacro arguments and frame prefix.
        index: Package index for ``$(find)`` and ``package://``.
        namespace: Namespace of this robot's nodes ("/" for a single robot).
        external: Joint states come from the bus (no joint_state_publisher, no sliders).
        state_publisher: Run a robot_state_publisher for the robot (off when the process that
            publishes the joint states runs its own, as ``robomodel sim`` and ``control run``).
    """

    def __init__(
        self,
        number: int,
        source: RobotSource,
        *,
        index: PackageIndex,
        namespace: str = "/",
        external: bool = False,
        state_publisher: bool = True,
    ) -> None:
        self.number = number
        self.source = source
        self.prefix = source.prefix
        # the TF Prefix of the RobotModel display that draws it (None: none does); set by
        # show_robots, read by frame_prefix
        self.tf_prefix: str | None = None
        self.link_updates = LinkUpdates()  # its Update Interval
        self.index = index.with_workspace_of(source.path) if source.path else index
        self.namespace = namespace
        self.external = external if source.external is None else source.external
        topic = source.joint_states_topic
        self._remappings = {"joint_states": topic} if topic else {}
        # Sliders without a robot_state_publisher: another node of the process (a launch file's
        # robot_state_publisher) turns their /joint_states into /tf.
        # A description from a topic comes from a robot_state_publisher, which publishes /tf.
        self.state_publisher = state_publisher and not source.topic
        self._publishers_created = False
        self.robot: Robot | None = None
        self.loaded: LoadedDescription | None = None
        self.failure: LoadFailure | None = None
        self.watcher: FileWatcher | TopicWatcher = (
            TopicWatcher(source.topic) if source.topic else FileWatcher([source.path])
        )
        self.rsp: RobotStatePublisher | None = None
        self.jsp: JointStatePublisher | None = None
        self.display: RobotModelDisplay | None = None
        self._pose_solver: LinkPoseSolver | None = None
        self.last_poses: LinkPoses | None = None  # at the last placement
        self.panel: JointPanel | None = None
        self.bodies: dict[str, BodyPose] = {}
        self.stale_frames: set[str] = set()
        self.generation = 0
        self._context: Context | None = None
        self._node: Node | None = None
        self._tf_pub: Any = None
        self._pending: dict[str, float] = {}
        self._has_bodies = False
        self._pending_lock = threading.Lock()

    # -- loading ------------------------------------------------------------------------------
    @property
    def label(self) -> str:
        name = (
            self.robot.name
            if self.robot is not None
            else (self.source.topic or Path(self.source.path).name)
        )
        # the prefix its frames have where it is drawn: a topic's robot has its display's
        prefix = self.frame_prefix
        return f"{prefix}{name}" if prefix else name

    @property
    def description_topic(self) -> str:
        """Where the robot's description is published: its topic, or ``robot_description`` in
        its namespace (robot_state_publisher's; RViz's RobotModel's Description Topic)."""
        if self.source.topic is not None:
            return "/" + self.source.topic.strip("/")
        return posixpath.join("/", self.namespace.strip("/"), "robot_description")

    @property
    def description_names(self) -> tuple[str, ...]:
        """The names an RViz RobotModel may give the description: its topic and, from a ROS 1
        launch, the parameter it was read from (global names)."""
        names = [self.description_topic]
        if self.source.description_name:
            names.append("/" + self.source.description_name.strip("/"))
        return tuple(dict.fromkeys(names))

    @property
    def frame_prefix(self) -> str:
        """What the robot's link names are prefixed with in TF where it is drawn: its RobotModel
        display's TF Prefix and a slash, as RViz looks link L up at ``<TF Prefix>/L``
        (rviz_default_plugins robot/tf_link_updater.cpp); the robot's own frame prefix when
        that is empty or names the same prefix (``robot1`` for ``robot1/``, ``r1_`` for
        ``r1_``: where the viewer's own robot_state_publisher puts it)."""
        tf_prefix = (self.tf_prefix or "").strip("/")
        if not tf_prefix or tf_prefix == self.prefix.strip("/"):
            return self.prefix
        return tf_prefix + "/"

    @property
    def root_frame(self) -> str | None:
        if self.robot is None:
            return None
        return self.frame_prefix + self.robot.tree().root

    def link_frames(self) -> tuple[str, ...]:
        if self.robot is None:
            return ()
        return tuple(self.frame_prefix + name for name in self.robot.link_names)

    def try_load(self) -> bool:
        """Expand and parse the description; on failure keep the last model and the error."""
        text = self.watcher.text if isinstance(self.watcher, TopicWatcher) else None
        if isinstance(self.watcher, TopicWatcher) and text is None:
            self.failure = LoadFailure(f"waiting for a robot description on {self.source.topic}")
            return False
        try:
            result, loaded = read_description(
                text if text is not None else self.source.path,
                args=dict(self.source.mappings),
                package_index=self.index,
            )
            result.robot.tree()  # a loop or several roots cannot be drawn
        except RobomodelError as exc:
            self.failure = LoadFailure.from_error(exc)
            if self.failure.path is not None:
                self.watcher.add([self.failure.path])
            return False
        self.failure = None
        old = self.robot
        self.robot, self.loaded = result.robot, loaded
        self.watcher.watch([self.source.path, *loaded.dependencies])
        if old is not None:
            self.stale_frames |= {self.prefix + n for n in old.link_names} - set(self.link_frames())
        self.stale_frames -= set(self.link_frames())
        self.generation += 1
        self._has_bodies = any(
            j.type in (JointType.FLOATING, JointType.PLANAR) for j in self.robot.joints
        )
        return True

    # -- running ------------------------------------------------------------------------------
    def start_nodes(self, context: Context, node: Node) -> None:
        """Create robot_state_publisher (and joint_state_publisher) for the loaded model."""
        self._context, self._node = context, node
        self._tf_pub = node.create_publisher(TFMessage, "/tf", 100)
        if isinstance(self.watcher, TopicWatcher):
            self.watcher.subscribe(node)
        if self.robot is None:
            return
        try:
            self._create_publishers()
        except RobomodelError as exc:  # e.g. a joint without limits: show it, keep serving
            self.failure = LoadFailure.from_error(exc)

    def _create_publishers(self) -> None:
        assert self._context is not None and self.robot is not None
        if self.state_publisher:
            self.rsp = RobotStatePublisher(
                self._context,
                self.robot,
                namespace=self.namespace,
                # A viewer must not drop slider moves: limit to 1000 Hz, not RSP's 20 Hz default.
                parameters={"frame_prefix": self.prefix, "publish_frequency": 1000.0},
                remappings=self._remappings,
            )
        self._publishers_created = True
        if not self.external:
            self.jsp = JointStatePublisher(
                self._context, self.robot, namespace=self.namespace, remappings=self._remappings
            )
            self.jsp.publish()

    def apply_reload(self) -> None:
        """Hand the newly loaded model to the nodes (keeping joint values that still exist)."""
        if self.robot is None:
            return
        if not self._publishers_created:
            self._create_publishers()
            self.publish_bodies()
            return
        if self.rsp is not None:
            description = urdf_to_string(self.robot)
            result = self.rsp.node.set_parameters({"robot_description": description})
            if not result.successful:
                self.failure = LoadFailure(f"robot_state_publisher refused it: {result.reason}")
                return
        if self.jsp is not None:
            self.jsp.configure(self.robot)
            self.jsp.publish()
        self.bodies = {k: v for k, v in self.bodies.items() if self._body_joint(k) is not None}
        self.publish_bodies()

    def build_display(
        self, scene: Any, meshes: MeshCache, options: DisplayOptions, *, load_meshes: bool
    ) -> None:
        if self.display is not None:
            self.display.remove()
            self.display = None
        self.last_poses = None
        self.link_updates.reset()  # a new drawing is placed at once, as RViz's load does
        if self.robot is None or self.loaded is None:
            return
        self.display = RobotModelDisplay(
            scene,
            f"/robots/r{self.number}g{self.generation}",
            self.robot,
            index=self.index,
            base_dir=self.loaded.base_dir,
            meshes=meshes,
            alpha=options.alpha,
            show_visual=options.show_visual,
            show_collision=options.show_collision,
        )
        self.display.build()
        if load_meshes:
            self.display.load_meshes()

    # -- poses --------------------------------------------------------------------------------
    def link_poses(
        self, buffer: BufferCore, fixed_frame: str, T_fixed_root_default: NDArray[np.float64]
    ) -> LinkPoses | None:
        """Every link in the fixed frame (see :class:`LinkPoseSolver`); None before a model."""
        if self.robot is None or self.display is None:
            return None
        solver = self._pose_solver
        prefix = self.frame_prefix
        if (
            solver is None
            or solver.robot is not self.robot
            or solver.link_names is not self.display.link_names
            or solver.prefix != prefix
        ):
            solver = LinkPoseSolver(self.robot, prefix, self.display.link_names)
            self._pose_solver = solver
        self.last_poses = solver.solve(buffer, fixed_frame, T_fixed_root_default)
        return self.last_poses

    def close(self) -> None:
        if self.display is not None:
            self.display.remove()
        if self.panel is not None:
            self.panel.remove()

    def close_nodes(self) -> None:
        """End the description subscription and the /tf publisher (a robot from a description
        topic that the viewer drops while it runs: its RobotModel display removed)."""
        if isinstance(self.watcher, TopicWatcher):
            self.watcher.unsubscribe()
        if self._tf_pub is not None:
            self._tf_pub.destroy()
            self._tf_pub = None
