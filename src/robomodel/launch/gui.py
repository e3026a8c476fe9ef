"""The launch's GUI: one browser viewer for every node whose role it plays (rviz, the
joint_state_publisher GUIs, gzclient, the rqt tools), or, headless, a joint_state_publisher
standing in for the sliders so that /tf stays complete."""

from __future__ import annotations

import functools
import os
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from robomodel.launch.nodes.base import ViewerRobot

__all__ = ["LaunchGui"]


class LaunchGui:
    """Started by the runner after its nodes (see the module docstring)."""

    def __init__(self, runner: Any) -> None:
        self.runner = runner
        self.viewer: Any = None

    def start(self) -> None:
        """The viewer; headless, the sliders' joint states come from a joint_state_publisher
        (what the sliders publish before anyone moves them), so /tf is complete."""
        if not self.runner.request.requested_by:
            return
        if not self.runner.options.headless:
            self._start_viewer()
        elif self.runner.request.sliders:
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
                    self.runner.context,
                    read_urdf(text).robot,
                    name=robot.slider_node_name,
                    namespace=robot.namespace,
                    remappings={"joint_states": robot.joint_states_topic},
                )
            )
        if publishers:
            self.runner._extra["headless_sliders"] = publishers
            self.runner.log(
                "[launch] headless: the sliders' joint states come from a joint_state_publisher"
            )

    def _robots(self) -> list[tuple[ViewerRobot, str]]:
        """The robots to draw with their URDF text: those the launch's robot_state_publishers
        and slider nodes name (one a namespace); without any, the description rviz or gazebo
        asked for, at the root."""
        from robomodel.launch.nodes.base import ViewerRobot

        request = self.runner.request
        found: list[tuple[ViewerRobot, str]] = []
        for robot in request.robots:
            text = robot.description_text
            param = robot.description_param
            if text is None and param and self.runner.params is not None:
                text = str(self.runner.params.get(param)) if self.runner.params.has(param) else None
            if text is None:
                self.runner.log(f"[launch] the viewer has no robot to show in {robot.namespace}")
                continue
            found.append((robot, text))
        if found or request.robots:
            return found
        text = self._description_text()
        param = request.robot_description_param
        return [] if text is None else [(ViewerRobot(request.namespace, description_param=param), text)]  # fmt: skip

    def _description_text(self) -> str | None:
        text: str | None = self.runner.request.robot_description_text
        if text is not None:
            return text
        param = self.runner.request.robot_description_param or "/robot_description"
        if self.runner.params is None or not self.runner.params.has(param):
            self.runner.log(
                f"[launch] {param} is not set: the viewer starts with no robot, as rviz does "
                "(its RobotModel displays bring them)"
            )
            return None
        return str(self.runner.params.get(param))

    def _start_viewer(self) -> None:
        try:
            from robomodel.viewer import Viewer, ViewerOptions
        except ImportError as exc:
            self.runner.log(f"[launch] no viewer: {exc}")
            return
        robots = self._robots()  # none: RViz's empty start
        sources = tuple(self._source(robot, text) for robot, text in robots)
        document = self.runner._extra.get("rviz")  # the rviz node's -d config
        settings = document.settings if document is not None else None
        server = self.runner._extra.get("sim_server")
        scenery: tuple[Any, ...] = ()
        scenery_source: Callable[[], tuple[Any, ...]] | None = None
        if server is not None:  # gzclient draws the world's objects too, spawned ones included
            scenery = _world_scenery(server)
            scenery_source = functools.partial(_world_scenery, server)

        fixed_frame = settings.fixed_frame if settings is not None else None
        options = ViewerOptions(
            sources=sources,
            port=self.runner.options.port,
            bus=self.runner.options.bus,
            domain_id=self.runner.options.domain_id,
            external=not any(r.joint_states_topic for r, _ in robots),
            state_publisher=False,  # the launch's robot_state_publisher publishes /tf
            package_index=self.runner.options.package_index or _default_index(),
            tools=self.runner.request.tools or True,
            fixed_frame=fixed_frame or self.runner.request.fixed_frame,
            scenery=scenery,
            scenery_source=scenery_source,
            frame_rate_hz=(settings.frame_rate_hz or 60.0) if settings is not None else 60.0,
            rviz=document,
        )
        self.viewer = Viewer(options)
        self.viewer.start()
        panel = getattr(self.viewer, "tools", None)
        if self.runner.request.plot_fields and panel is not None:
            threading.Thread(
                target=_add_plots, args=(panel, list(self.runner.request.plot_fields)), daemon=True
            ).start()
        if self.runner.request.steering_topic and panel is not None:
            panel.steering.topic.value = self.runner.request.steering_topic
        self.runner.log(f"[launch] viewer: serving {self.viewer.url}")
        if self.runner.options.open_browser:
            import webbrowser

            webbrowser.open(self.viewer.url)

    def _source(self, robot: ViewerRobot, text: str) -> Any:
        """A viewer source for one robot: its URDF in a temporary file, its frames' prefix,
        and its sliders' topic (none: its joint states come from the bus)."""
        from robomodel.viewer import RobotSource

        handle, path = tempfile.mkstemp(prefix="robomodel_launch_", suffix=".urdf")
        with os.fdopen(handle, "w", encoding="utf-8") as out:
            out.write(text)
        self.runner._extra.setdefault("viewer_files", []).append(path)
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
        for sliders in self.runner._extra.get("headless_sliders", ()):
            sliders.node.destroy()
        for path in self.runner._extra.get("viewer_files", ()):
            Path(path).unlink(missing_ok=True)


def _world_scenery(server: Any) -> tuple[Any, ...]:
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


def _default_index() -> Any:
    from robomodel.description.packages import PackageIndex

    return PackageIndex()
