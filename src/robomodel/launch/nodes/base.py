"""How a launch file's node becomes a robomodel component: a registry of factories.

A factory takes a :class:`NodeContext` (the node's spec, its parameters as the real node would
see them, the launch's bus and viewer) and returns a :class:`RunningNode`. A node robomodel does
not provide has no factory: the runner reports it once and goes on.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

from robomodel.description.packages import PackageIndex
from robomodel.launch.model import NodeSpec

if TYPE_CHECKING:
    from robomodel.viewer.rviz_document import RvizDocument

__all__ = [
    "LaunchShared",
    "NodeContext",
    "RunningNode",
    "SharedSimulator",
    "ThreadNode",
    "ViewerRequest",
    "ViewerRobot",
    "factory_for",
    "plot_fields",
    "register",
    "supported",
]


class RunningNode(Protocol):
    """A started node."""

    def stop(self) -> None:
        """End it (idempotent)."""

    def exit_code(self) -> int | None:
        """None while it runs; its exit code once it ended."""


class ThreadNode:
    """A node that does its work in a thread, as its own process would, then ends."""

    def __init__(
        self, name: str, work: Callable[[ThreadNode], int], log: Callable[[str], None]
    ) -> None:
        self._code: int | None = None
        self.error = ""
        self.log = log
        self.stopping = threading.Event()
        self._thread = threading.Thread(target=self._run, args=(work,), name=name, daemon=True)
        self._thread.start()

    def _run(self, work: Callable[[ThreadNode], int]) -> None:
        try:
            self._code = int(work(self))
        except Exception as exc:  # what a crashing process would print
            self._code = 1
            self.error = str(exc)
            self.log(f"ended with an error: {exc}")

    def stop(self) -> None:
        self.stopping.set()

    def exit_code(self) -> int | None:
        return self._code


@dataclass
class ViewerRobot:
    """One robot the viewer draws, as the launch's nodes in its namespace describe it.

    ``joint_states_topic`` is set when a joint_state_publisher_gui (or ``use_gui``) runs there:
    the fully resolved topic its sliders publish on (its namespace and remaps applied, as the
    real node's ``joint_states`` publisher resolves). ``frame_prefix`` is the robot_state_publisher's
    (ROS 2 ``frame_prefix``, ROS 1 ``tf_prefix``), so the viewer finds the robot's frames in /tf.
    """

    namespace: str
    description_text: str | None = None
    description_param: str | None = None
    frame_prefix: str = ""
    joint_states_topic: str | None = None
    slider_node_name: str = "joint_state_publisher_gui"  # the launch file's name for it


@dataclass
class ViewerRequest:
    """What the launch's viewer must show (RViz's and the GUIs' roles, merged)."""

    robot_description_param: str | None = None
    sliders: bool = False
    tools: bool = False
    fixed_frame: str | None = None
    frame_rate_hz: float | None = None
    background: tuple[int, int, int] | None = None
    show_robot: bool = True
    show_tf: bool = True
    unsupported_displays: list[str] = field(default_factory=list)
    namespace: str = "/"
    joint_states_topic: str = "/joint_states"
    steering_topic: str | None = None  # rqt_robot_steering's ~default_topic
    robot_description_text: str | None = None  # ROS 2: no parameter server to read it from
    plot_fields: list[str] = field(default_factory=list)  # rqt_plot's topic/field arguments
    requested_by: list[str] = field(default_factory=list)
    robots: list[ViewerRobot] = field(default_factory=list)  # in launch order, one a namespace

    def robot(self, namespace: str) -> ViewerRobot:
        """The robot of ``namespace`` (``/`` or ``/a/b``), added on first use."""
        found = next((r for r in self.robots if r.namespace == namespace), None)
        if found is None:
            found = ViewerRobot(namespace)
            self.robots.append(found)
        return found


class SharedSimulator(Protocol):
    """gzserver's simulator as the launch's GUI sees it (a robomodel.sim.server.SimServer)."""

    @property
    def world(self) -> Any:
        """The current world (robomodel.sim.World), spawned models included."""


@dataclass
class LaunchShared:
    """What the nodes of one launch share with each other and with its GUI.

    The runner makes one a launch and hands it to every node's :class:`NodeContext` and to the
    :class:`~robomodel.launch.gui.LaunchGui`; the nodes that play a part others look for
    (gzserver's simulator, rviz's display config) set it here.

    Attributes:
        package_index: Where packages are found (the launch's, else the environment's).
        nodes: Every node of the launch, in file order (hints and lookups of peers).
        launch_file: The launch file run, if any (hints name it).
        sim_server: The simulator gzserver started (one a launch; gzclient draws its world).
        rviz: The rviz node's ``-d`` display config (the viewer shows it).
    """

    package_index: PackageIndex = field(default_factory=PackageIndex)
    nodes: tuple[NodeSpec, ...] = ()
    launch_file: str | None = None
    sim_server: SharedSimulator | None = None
    rviz: RvizDocument | None = None


@dataclass
class NodeContext:
    """Everything a factory needs for one node."""

    spec: NodeSpec
    runtime: Any  # robomodel.runtime.Context: the launch's bus
    params: Any  # the ROS 1 parameter server (ParamServer or RemoteParamServer)
    viewer: ViewerRequest
    log: Callable[[str], None]
    shared: LaunchShared = field(default_factory=LaunchShared)

    @property
    def namespace(self) -> str:
        """The node's namespace in the runtime's form (``/`` or ``/a/b``, no trailing slash)."""
        ns = self.spec.namespace.rstrip("/")
        return ns or "/"

    def ros2_parameters(self, default_name: str) -> dict[str, Any]:
        """A ROS 2 node's parameters from its launch sources (``default_name``: its name when
        the launch file gives none)."""
        from robomodel.launch.nodes.ros2_params import node_parameters

        return node_parameters(self.spec, name=default_name)

    @property
    def use_sim_time(self) -> bool:
        """ROS 1's global ``/use_sim_time`` (set by gazebo_ros's launch files): the node's
        clock is /clock."""
        value = self.params.get("/use_sim_time") if self.params.has("/use_sim_time") else False
        return value is True or str(value).lower() == "true"

    def resolve(self, name: str) -> str:
        """A ROS 1 parameter name for this node: ``~x`` private, ``x`` relative, ``/x``."""
        if name.startswith("/"):
            return name
        if name.startswith("~"):
            return self.spec.fqn + "/" + name[1:]
        return self.spec.namespace.rstrip("/") + "/" + name

    def resolve_name(self, name: str) -> str:
        """A topic or service name as the node's own client library resolves it: relative
        names in its namespace, ``~`` in its name, then its remaps (whose sides are resolved
        the same way), as roscpp's ``names::resolve`` and rcl's expansion and remapping do."""
        from robomodel.runtime.names import apply_remappings, expand_topic_name

        node_name = self.spec.name or self.spec.executable
        expanded = expand_topic_name(name, node_name, self.namespace)
        return apply_remappings(expanded, self.remappings, node_name, self.namespace)

    def param(self, name: str, default: Any = None) -> Any:
        key = self.resolve(name)
        return self.params.get(key) if self.params.has(key) else default

    def search(self, name: str) -> str | None:
        """roscpp's searchParam from the node's namespace (robot_description lookups)."""
        found: str | None = self.params.search(self.spec.fqn, name)
        return found

    @property
    def remappings(self) -> dict[str, str]:
        return dict(self.spec.remaps)


Factory = Callable[[NodeContext], RunningNode]
_REGISTRY: dict[tuple[str, str, str], Factory] = {}
_PURPOSE: dict[tuple[str, str, str], str] = {}


def register(
    dialect: str, package: str, *executables: str, purpose: str = ""
) -> Callable[[Factory], Factory]:
    """Register a factory for ``package``/``executable`` nodes of a dialect (``ros1``/``ros2``)."""

    def decorate(factory: Factory) -> Factory:
        for executable in executables:
            _REGISTRY[(dialect, package, executable)] = factory
            _PURPOSE[(dialect, package, executable)] = purpose
        return factory

    return decorate


def plot_fields(args: tuple[str, ...]) -> list[str]:
    """rqt_plot's arguments as field paths: ``/t/a`` stays, ``/t/pose/x:y`` is ``/t/pose/x``
    and ``/t/pose/y``, options and ROS arguments are left out."""
    fields: list[str] = []
    for arg in args:
        if arg.startswith(("-", "__")) or ":=" in arg:
            continue
        head, _, tail = arg.partition(":")
        fields.append(head)
        if tail:
            base = head.rsplit("/", 1)[0]
            fields.extend(f"{base}/{name}" for name in tail.split(":") if name)
    return fields


def factory_for(spec: NodeSpec) -> Factory | None:
    return _REGISTRY.get((spec.dialect, spec.package, spec.executable))


def supported(dialect: str) -> list[tuple[str, str, str]]:
    """``(package, executable, what robomodel runs for it)`` for the README's table and errors."""
    return sorted((p, e, _PURPOSE[(d, p, e)]) for d, p, e in _REGISTRY if d == dialect)
