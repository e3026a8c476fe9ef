"""The launch's GUI: one browser viewer for every node whose role it plays (rviz, the
joint_state_publisher GUIs, gzclient, the rqt tools), or, headless, a joint_state_publisher
standing in for the sliders so that /tf stays complete.

The GUI reads what the launch's nodes asked of it (:class:`ViewerRequest`) and what they
share (:class:`LaunchShared`: rviz's display config, gzserver's simulator, the package index);
the runner gives it those, its options and the launch's bus when it starts the nodes.
"""

from __future__ import annotations

import functools
import os
import tempfile
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from robomodel.launch.nodes.base import LaunchShared, SharedSimulator, ViewerRequest, ViewerRobot

if TYPE_CHECKING:
    from robomodel.runtime import Context
    from robomodel.runtime.nodes.joint_state_publisher import JointStatePublisher
    from robomodel.viewer import RobotSource, Viewer

__all__ = ["GuiOptions", "LaunchGui", "ParamLookup"]


@dataclass(frozen=True, slots=True)
class GuiOptions:
    """How the launch shows its GUI (``robomodel launch``'s options).

    Attributes:
        headless: No viewer; sliders are stood in for by a joint_state_publisher.
        open_browser: Open the viewer's page in a browser.
        port: The viewer's HTTP port.
        bus: The viewer's bus (``zenoh``, ``ros1``, ``inproc``).
        domain_id: The ROS domain of the Zenoh bus (None: the environment's).
    """

    headless: bool = False
    open_browser: bool = True
    port: int = 8080
    bus: str = "zenoh"
    domain_id: int | None = None


class ParamLookup(Protocol):
    """The launch's parameter server, as the GUI reads it (robot descriptions)."""

    def has(self, name: str) -> bool:
        """Whether ``name`` is set."""

    def get(self, name: str) -> Any:
        """The value of ``name`` (set)."""


class LaunchGui:
    """Started by the runner after its nodes (see the module docstring)."""

    def __init__(
        self,
        options: GuiOptions,
        request: ViewerRequest,
        shared: LaunchShared,
        *,
        context: Context,
        params: ParamLookup | None,
        log: Callable[[str], None],
    ) -> None:
        self.options = options
        self.request = request
        self.shared = shared
        self.context = context
        self.params = params
        self.log = log
        self.viewer: Viewer | None = None
        self._headless_sliders: list[JointStatePublisher] = []
        self._viewer_files: list[str] = []  # the robots' URDF files, removed on close

    def start(self) -> None:
        """The viewer; headless, the sliders' joint states come from a joint_state_publisher
        (what the sliders publish before anyone moves them), so /tf is complete."""
        if not self.request.requested_by:
            return
        if not self.options.headless:
            self._start_viewer()
        elif self.request.sliders:
            self._start_headless_sliders()

    def _start_headless_sliders(self) -> None:
        from robomodel.description import read_urdf
        from robomodel.runtime.nodes.joint_state_publisher import JointStatePublisher

        publishers = []
        for robot, text in self._robots():
            if robot.joint_states_topic is None:
                continue
            publishers.append(
                JointStatePublisher(
                    self.context,
                    read_urdf(text).robot,
                    name=robot.slider_node_name,
                    namespace=robot.namespace,
                    remappings={"joint_states": robot.joint_states_topic},
                )
            )
        if publishers:
            self._headless_sliders = publishers
            self.log(
                "[launch] headless: the sliders' joint states come from a joint_state_publisher"
            )

    def _robots(self) -> list[tuple[ViewerRobot, str]]:
        """The robots to draw with their URDF text: those the launch's robot_state_publishers
        and slider nodes name (one a namespace); without any, the description rviz or gazebo
        asked for, at the root."""
        request = self.request
        found: list[tuple[ViewerRobot, str]] = []
        for robot in request.robots:
            text = robot.description_text
            param = robot.description_param
            if text is None and param and self.params is not None:
                text = str(self.params.get(param)) if self.params.has(param) else None
            if text is None:
                self.log(f"[launch] the viewer has no robot to show in {robot.namespace}")
                continue
            found.append((robot, text))
        if found or request.robots:
            return found
        text = self._description_text()
        param = request.robot_description_param
        return [] if text is None else [(ViewerRobot(request.namespace, description_param=param), text)]  # fmt: skip

    def _description_text(self) -> str | None:
        text: str | None = self.request.robot_description_text
        if text is not None:
            return text
        param = self.request.robot_description_param or "/robot_description"
        if self.params is None or not self.params.has(param):
            self.log(
                f"[launch] {param} is not set: the viewer starts with no robot, as rviz does "
                "(its RobotModel displays bring them)"
            )
            return None
        return str(self.params.get(param))

    def _start_viewer(self) -> None:
        try:
            from robomodel.viewer import Viewer, ViewerOptions
        except ImportError as exc:
            self.log(f"[launch] no viewer: {exc}")
            return
        robots = self._robots()  # none: RViz's empty start
        sources = tuple(self._source(robot, text) for robot, text in robots)
        document = self.shared.rviz  # the rviz node's -d config
        settings = document.settings if document is not None else None
        server = self.shared.sim_server
        scenery: tuple[Any, ...] = ()
        scenery_source: Callable[[], tuple[Any, ...]] | None = None
        if server is not None:  # gzclient draws the world's objects too, spawned ones included
            scenery = _world_scenery(server)
            scenery_source = functools.partial(_world_scenery, server)

        fixed_frame = settings.fixed_frame if settings is not None else None
        options = ViewerOptions(
            sources=sources,
            port=self.options.port,
            bus=self.options.bus,
            domain_id=self.options.domain_id,
            external=not any(r.joint_states_topic for r, _ in robots),
            state_publisher=False,  # the launch's robot_state_publisher publishes /tf
            package_index=self.shared.package_index,
            tools=self.request.tools or True,
            fixed_frame=fixed_frame or self.request.fixed_frame,
            scenery=scenery,
            scenery_source=scenery_source,
            frame_rate_hz=(settings.frame_rate_hz or 60.0) if settings is not None else 60.0,
            rviz=document,
        )
        viewer = self.viewer = Viewer(options)
        viewer.start()
        panel = viewer.tools
        if self.request.plot_fields and panel is not None:
            threading.Thread(
                target=_add_plots, args=(panel, list(self.request.plot_fields)), daemon=True
            ).start()
        if self.request.steering_topic and panel is not None:
            panel.steering.topic.value = self.request.steering_topic
        self.log(f"[launch] viewer: serving {viewer.url}")
        if self.options.open_browser:
            import webbrowser

            webbrowser.open(viewer.url)

    def _source(self, robot: ViewerRobot, text: str) -> RobotSource:
        """A viewer source for one robot: its URDF in a temporary file, its frames' prefix,
        and its sliders' topic (none: its joint states come from the bus)."""
        from robomodel.viewer import RobotSource

        handle, path = tempfile.mkstemp(prefix="robomodel_launch_", suffix=".urdf")
        with os.fdopen(handle, "w", encoding="utf-8") as out:
            out.write(text)
        self._viewer_files.append(path)
        return RobotSource(
            path,
            prefix=robot.frame_prefix,
            namespace=robot.namespace,
            joint_states_topic=robot.joint_states_topic,
            external=robot.joint_states_topic is None,
            description_name=robot.description_param,
        )

    def close(self) -> None:
        if self.viewer is not None:
            self.viewer.close()
        for sliders in self._headless_sliders:
            sliders.node.destroy()
        for path in self._viewer_files:
            Path(path).unlink(missing_ok=True)


def _world_scenery(server: SharedSimulator) -> tuple[Any, ...]:
    """The simulator server's current world as the viewer's scenery (it changes on spawns)."""
    from robomodel.sim.scenery import scenery_of

    return scenery_of(server.world)


def _add_plots(panel: Any, fields: list[str], timeout_s: float = 15.0) -> None:
    """rqt_plot's fields into the Plot folder, each once its topic is on the bus."""
    from robomodel.errors import RobomodelError
    from robomodel.viewer.tools.field_path import resolve_field_path

    deadline = time.monotonic() + timeout_s
    pending = list(fields)
    while pending and time.monotonic() < deadline:
        for text in list(pending):
            try:
                resolve_field_path(text, panel.tools.topic_types())
            except RobomodelError:
                continue
            panel.plot.add(text)
            pending.remove(text)
        time.sleep(0.5)
    for text in pending:  # what the Plot folder says of it
        panel.plot.add(text)
