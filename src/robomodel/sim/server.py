"""A simulation server that robots are spawned into while it runs: ``gzserver`` + the
``/gazebo/spawn_urdf_model`` service, for launch files.

``robomodel sim`` knows its robots before it starts; a launch file starts the world first
(``gazebo_ros`` ``empty_world.launch``) and spawns robots into it afterwards (``spawn_model``),
possibly from another process. :class:`SimServer` owns the world, the robots spawned so far and
their controller managers (one per robot, as ``gazebo_ros_control`` runs one in the robot's
``robotNamespace``), and is driven by its owner's loop (:meth:`SimServer.drive`), which also
runs the bus callbacks, so that physics, controllers and service handlers share one thread.

MuJoCo compiles a whole scene at once, so a spawn recompiles it: the robots already there keep
their joint positions and velocities, the time goes on, and their controllers are loaded again
in the state they had.

The gazebo_msgs services that call into the server are in
:mod:`robomodel.sim.server_services`.
"""

from __future__ import annotations

import dataclasses
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robomodel.errors import RobomodelError
from robomodel.sim.build.robot import Placement
from robomodel.sim.exceptions import SimulationError
from robomodel.sim.server_control import Controllers, carry_state, namespace_of, start_control
from robomodel.sim.server_services import service_handlers

if TYPE_CHECKING:
    from robomodel.control import ControlSystem
    from robomodel.control.config import ControllerSpec
    from robomodel.description.model import Robot
    from robomodel.description.packages import PackageIndex
    from robomodel.runtime.context import Context
    from robomodel.sim.bus import SimBridge
    from robomodel.sim.engine import Simulation
    from robomodel.sim.world import World

__all__ = ["SimServer", "SpawnedRobot"]

SpecSource = Callable[[str, str], "ControllerSpec | None"]  # (manager namespace, name)
_CHUNK_S = 0.01  # physics between two bus spins [s of sim time]


@dataclass
class SpawnedRobot:
    """A robot in the server's world: its model name, description and placement."""

    model_name: str
    robot: Robot
    placement: Placement
    robot_namespace: str = "/"
    control: ControlSystem | None = None


class SimServer:
    """Gazebo's server role for launch files (see the module docstring).

    Args:
        world: The world (``worlds/empty.world`` is :func:`~robomodel.sim.default_world`).
        context: The bus (wall clock; nodes with ``use_sim_time`` follow ``/clock``).
        package_index: Where ``package://`` meshes of spawned robots are found.
        paused: Start paused (``gzserver -u``); ``/gazebo/unpause_physics`` starts it.
        real_time_factor: Pace (``None``: as fast as possible).
        spec_source: Controller parameters by (manager namespace, controller name), for
            spawners that name controllers the manager was not configured with (a ROS 1
            launch's parameter server).
        ros_version: Whose gazebo_ros service names to offer (1: ``/gazebo/...`` only; 2: also
            ROS 2's root-level ones); None: from the bus (see :class:`SimBridge`).
    """

    def __init__(
        self,
        world: World,
        *,
        context: Context,
        package_index: PackageIndex,
        paused: bool = False,
        real_time_factor: float | None = 1.0,
        spec_source: SpecSource | None = None,
        ros_version: int | None = None,
    ) -> None:
        self.world = world
        self.ros_version = ros_version or (1 if getattr(context, "bus", "") == "ros1" else 2)
        self.context = context
        self.index = package_index
        self.real_time_factor = real_time_factor
        self.spec_source = spec_source
        self.robots: list[SpawnedRobot] = []
        self.sim: Simulation | None = None
        self.bridge: SimBridge | None = None
        self._paused = paused
        # A spawn or delete served on another thread (an in-process call runs the handler in
        # the caller's thread: spawn_model's) rebuilds the scene; it waits for the chunk being
        # stepped, so the drive loop never steps a half-built simulation or bridge.
        self._scene_lock = threading.RLock()
        # Rebuilds waiting for the lock: the drive loop lets them in first (a lock is not fair,
        # and a loop that cannot keep real time would take it again at once, forever)
        self._waiting = 0
        self._waiting_lock = threading.Lock()
        self._anchor: tuple[float, float] | None = None
        self.node = context.create_node("gazebo")
        self._rebuild()
        for name, srv_type, handler in service_handlers(self):
            self.node.create_service(srv_type, name, handler)

    # -- spawning -------------------------------------------------------------------------------
    def spawn(
        self,
        model_name: str,
        urdf_xml: str,
        *,
        xyz_m: tuple[float, float, float] = (0.0, 0.0, 0.0),
        rpy_rad: tuple[float, float, float] = (0.0, 0.0, 0.0),
        joint_positions: dict[str, float] | None = None,
        robot_namespace: str = "/",
    ) -> SpawnedRobot:
        """Add a robot (``spawn_model -urdf``) and recompile the scene.

        ``robot_namespace`` is where its controller manager runs when its control plugin names
        no ``robotNamespace`` (``spawn_model -robot_namespace``, default the spawner's
        namespace: gazebo_ros adds it to every plugin of the model).

        Raises:
            SimulationError: a model of that name exists, or the robot cannot be simulated.
            RobomodelError: the URDF is invalid.
        """
        from robomodel.description import read_urdf

        if any(r.model_name == model_name for r in self.robots):
            raise SimulationError(
                f"a model named '{model_name}' is already in the world (models are: "
                f"{', '.join(r.model_name for r in self.robots)}); give -model another name"
            )
        robot = read_urdf(urdf_xml, path=f"<spawned model {model_name}>").robot
        # The first robot keeps its link names (Gazebo's frames are the URDF's); later ones are
        # told apart inside MuJoCo by their model name.
        prefix = "" if not self.robots else f"{model_name}/"
        entry = SpawnedRobot(
            model_name, robot, Placement(prefix, xyz_m, rpy_rad), "/" + robot_namespace.strip("/")
        )
        self._checknamespace_of(entry)
        self.robots.append(entry)
        try:
            self._rebuild()
        except RobomodelError:
            self.robots.remove(entry)
            self._rebuild()
            raise
        if joint_positions:
            self._set_joints(entry, joint_positions)
        return entry

    def _checknamespace_of(self, entry: SpawnedRobot) -> None:
        from robomodel.sim.build.gazebo import read_gazebo

        mine = read_gazebo(entry.robot)
        if not mine.ros_control_plugin:
            return
        namespace = namespace_of(mine.plugin_namespace, entry.robot_namespace)
        for other in self.robots:
            theirs = read_gazebo(other.robot)
            if theirs.ros_control_plugin and (
                namespace_of(theirs.plugin_namespace, other.robot_namespace) == namespace
            ):
                raise SimulationError(
                    f"model '{entry.model_name}' would run its controller manager in "
                    f"{namespace}, where model '{other.model_name}' runs one; give it another "
                    "namespace (spawn_model -robot_namespace, or the plugin's <robotNamespace>)"
                )

    def delete(self, model_name: str) -> None:
        """Remove a model (``/gazebo/delete_model``)."""
        names = [r.model_name for r in self.robots]
        if model_name not in names:
            from robomodel.errors import describe_unknown

            raise SimulationError(describe_unknown("model", model_name, names, "models are"))
        self.robots = [r for r in self.robots if r.model_name != model_name]
        self._rebuild()

    def model_names(self) -> list[str]:
        """The robots' and the SDF models' names (``get_world_properties``)."""
        names = [r.model_name for r in self.robots]
        return names + sorted({s.model for s in self.world.shapes if s.model not in names})

    def set_joint_positions(self, model_name: str, positions: dict[str, float]) -> None:
        """Set joints of a spawned robot (``set_model_configuration``, ``spawn_model -J``)."""
        for entry in self.robots:
            if entry.model_name == model_name:
                self._set_joints(entry, positions)
                return
        from robomodel.errors import describe_unknown

        names = [r.model_name for r in self.robots]
        raise SimulationError(describe_unknown("model", model_name, names, "models are"))

    def _set_joints(self, entry: SpawnedRobot, positions: dict[str, float]) -> None:
        from robomodel.sim._mujoco import mujoco

        mj = mujoco()
        assert self.sim is not None
        model, data = self.sim.model, self.sim.data
        for joint, value in positions.items():
            jid = mj.mj_name2id(model, mj.mjtObj.mjOBJ_JOINT, entry.placement.prefix + joint)
            if jid < 0:
                raise SimulationError(f"model '{entry.model_name}' has no joint '{joint}'")
            data.qpos[model.jnt_qposadr[jid]] = value
        mj.mj_forward(model, data)

    def spawn_sdf(
        self,
        model_name: str,
        sdf_xml: str,
        *,
        xyz_m: tuple[float, float, float] = (0.0, 0.0, 0.0),
        rpy_rad: tuple[float, float, float] = (0.0, 0.0, 0.0),
    ) -> None:
        """Add an SDF model of rigid shapes (``spawn_model -sdf``) to the world.

        Raises:
            WorldError: a model with joints or no shapes; SimulationError: a taken name.
        """
        from robomodel.sim.world import model_shapes

        taken = {s.model for s in self.world.shapes} | {r.model_name for r in self.robots}
        if model_name in taken:
            raise SimulationError(f"a model named '{model_name}' is already in the world")
        shapes = model_shapes(
            sdf_xml, name=model_name, pose=(*xyz_m, *rpy_rad), path=f"<spawned model {model_name}>"
        )
        if not shapes:
            raise SimulationError(f"SDF model '{model_name}' has no collision shapes")
        previous = self.world
        self.world = dataclasses.replace(previous, shapes=previous.shapes + shapes)
        try:
            self._rebuild()
        except RobomodelError:
            self.world = previous
            self._rebuild()
            raise

    # -- the scene -------------------------------------------------------------------------------
    def _rebuild(self) -> None:
        with self._waiting_lock:
            self._waiting += 1
        try:
            with self._scene_lock:
                self._rebuild_locked()
        finally:
            with self._waiting_lock:
                self._waiting -= 1

    def _rebuild_locked(self) -> None:
        from robomodel.sim.bus import SimBridge
        from robomodel.sim.engine import Simulation

        old = self.sim
        sim = Simulation(self.world, package_index=self.index)
        for entry in self.robots:
            sim.add_robot(entry.robot, placement=entry.placement)
        sim.build()
        if old is not None:
            carry_state(old, sim)
        previous: dict[str, Controllers] = {}
        for entry in self.robots:
            if entry.control is not None:
                manager = entry.control.manager
                states = {c["name"]: c["state"] for c in manager.list_controllers()}
                previous[entry.model_name] = Controllers(dict(manager.specs), states)
                manager.close()
                entry.control = None
        if self.bridge is not None:
            self.bridge.close()
        self.sim = sim
        for entry in self.robots:
            entry.control = start_control(self, sim, entry, previous.get(entry.model_name))
        self.bridge = SimBridge(
            sim,
            self.context,
            node_name="gazebo_physics",
            ros_version=self.ros_version,
            model_names={e.placement.prefix: e.model_name for e in self.robots},
        )
        self.bridge.paused = self._paused

    # -- running --------------------------------------------------------------------------------
    @property
    def paused(self) -> bool:
        return self.bridge.paused if self.bridge is not None else self._paused

    def drive(self, duration_s: float) -> None:
        """Run physics (paced) and the bus callbacks for ``duration_s`` of wall time."""
        assert self.sim is not None and self.bridge is not None
        end = time.perf_counter() + duration_s
        while time.perf_counter() < end:
            while self._waiting:  # a spawn from another thread goes first
                time.sleep(0.001)
            with self._scene_lock:
                sim, paused, stepped = self._chunk()
            if paused:
                if not stepped:
                    time.sleep(0.01)
                continue
            factor = self.real_time_factor
            anchor = self._anchor
            if factor is not None and factor > 0 and self.sim is sim and anchor is not None:
                delay = anchor[0] + (sim.time_s - anchor[1]) / factor - time.perf_counter()
                if delay > 0:
                    time.sleep(min(delay, max(0.0, end - time.perf_counter())))
            elif self.sim is not sim:
                self._anchor = None

    def _chunk(self) -> tuple[Simulation, bool, bool]:
        """One chunk of physics and bus callbacks (under the scene lock): the simulation it
        stepped, whether it was paused, whether it stepped (paused: only requested steps)."""
        sim, bridge = self.sim, self.bridge
        assert sim is not None and bridge is not None
        self._paused = paused = bridge.paused
        if paused:
            self._anchor = None
            bridge.poll()
            steps, bridge.pending_steps = bridge.pending_steps, 0
            if steps:
                sim.step(steps)
            return sim, True, bool(steps)
        if self._anchor is None:
            self._anchor = (time.perf_counter(), sim.time_s)
        sim.run(_CHUNK_S)
        self.context.spin_once(0.0)  # service handlers may rebuild: re-read sim next turn
        return sim, False, True

    def close(self) -> None:
        self.node.destroy()
        for entry in self.robots:
            if entry.control is not None:
                entry.control.manager.close()
        if self.bridge is not None:
            self.bridge.close()
