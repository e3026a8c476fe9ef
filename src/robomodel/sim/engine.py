"""The simulation: physics stepping, the controller managers in the loop, divergence checks.

One :class:`Simulation` holds a world and its robots, compiled into one MuJoCo model. Each
physics step runs, in Gazebo's order (gazebo_ros2_control ``Update`` on WorldUpdateBegin):
the callbacks due at this step (controller managers at their ``update_rate``: read, update,
write; sensors, /clock and ground truth at theirs), then every simulated hardware component
writes its kinematic commands, then ``mj_step``. NaN or infinite states (or MuJoCo's own
"bad qacc" reset) stop the run with a :class:`DivergenceError` naming the joint and body.
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from robomodel.sim._divergence import check_finite
from robomodel.sim._mujoco import mujoco
from robomodel.sim.build.geoms import MeshLoader
from robomodel.sim.build.robot import BuiltRobot, Placement, add_robot
from robomodel.sim.build.scene import add_world, apply_min_friction, new_spec
from robomodel.sim.exceptions import SimulationError
from robomodel.sim.schedule import (
    ActivePredicate,
    ScheduledCallback,
    StepCallback,
    StepSchedule,
)
from robomodel.sim.world import World, default_world

if TYPE_CHECKING:
    from robomodel.control import ControlSystem
    from robomodel.control.config import ControllerConfig
    from robomodel.control.manager import ControllerManager
    from robomodel.description.model import Robot
    from robomodel.description.packages import PackageIndex
    from robomodel.runtime.context import Context
    from robomodel.sim.hardware import SimSystem

__all__ = ["Simulation", "StepCallback"]

_CHECK_EVERY_STEPS = 100


class Simulation:
    """A world with robots on MuJoCo (see the module docstring).

    Add robots with :meth:`add_robot`, then controllers with :meth:`control`; the model is
    compiled on first use of :attr:`model` (or by :meth:`build`).

    Args:
        world: The world; :func:`~robomodel.sim.world.default_world` (ground and sun) by default.
        package_index: Resolves ``package://`` mesh paths.
        include_visuals: Also add visual geoms (for MuJoCo rendering; collision-free).
    """

    def __init__(
        self,
        world: World | None = None,
        *,
        package_index: PackageIndex | None = None,
        include_visuals: bool = False,
    ) -> None:
        from robomodel.description.packages import PackageIndex

        self.world = world or default_world()
        self._index = package_index or PackageIndex()
        self._include_visuals = include_visuals
        self._spec = new_spec(self.world)
        add_world(self._spec, self.world)
        self.robots: list[BuiltRobot] = []
        self._model: Any = None
        self._data: Any = None
        self._schedule = StepSchedule()
        self._hardware: list[SimSystem] = []
        self._controls: list[ControlSystem] = []
        self._steps = 0
        self._initial_qpos: np.ndarray | None = None

    # -- building ---------------------------------------------------------------------------
    def add_robot(
        self,
        robot: Robot,
        *,
        placement: Placement | None = None,
        base_dir: str | os.PathLike[str] | None = None,
    ) -> BuiltRobot:
        """Spawn ``robot`` (``spawn_entity``); prefixes must differ between robots.

        Raises:
            SimulationError: after :meth:`build`, a repeated prefix, or a robot that cannot be
                simulated (bad inertia with its file:line, missing meshes, ...).
        """
        if self._model is not None:
            raise SimulationError("robots must be added before the simulation is built")
        placement = placement or Placement()
        if any(r.prefix == placement.prefix for r in self.robots):
            raise SimulationError(
                f"a robot with prefix '{placement.prefix}' is already in the world; give each "
                "robot its own prefix"
            )
        if len(self.robots) >= 29:
            raise SimulationError("at most 29 robots per world (one collision bit each)")
        if base_dir is None and robot.source_path:
            base_dir = os.path.dirname(os.path.abspath(robot.source_path.split(" ")[0]))
        loader = MeshLoader(self._index, os.fspath(base_dir) if base_dir is not None else None)
        built = add_robot(
            self._spec,
            robot,
            placement=placement,
            bit=1 << (len(self.robots) + 1),
            loader=loader,
            include_visuals=self._include_visuals,
        )
        self.robots.append(built)
        return built

    def build(self) -> None:
        """Compile the model (idempotent)."""
        if self._model is not None:
            return
        mj = mujoco()
        apply_min_friction(self._spec, self.robots)
        try:
            self._model = self._spec.compile()
        except Exception as exc:  # MuJoCo raises ValueError with its compiler message
            raise SimulationError(f"MuJoCo cannot compile the scene: {exc}") from None
        self._data = mj.MjData(self._model)
        mj.mj_forward(self._model, self._data)
        self._initial_qpos = self._data.qpos.copy()

    @property
    def model(self) -> Any:
        """The compiled ``mujoco.MjModel``."""
        self.build()
        return self._model

    @property
    def data(self) -> Any:
        """The ``mujoco.MjData``."""
        self.build()
        return self._data

    @property
    def timestep_s(self) -> float:
        return float(self.world.timestep_s)

    @property
    def time_s(self) -> float:
        """Simulation time [s]."""
        return float(self.data.time)

    def robot(self, prefix: str = "") -> BuiltRobot:
        for built in self.robots:
            if built.prefix == prefix:
                return built
        from robomodel.errors import describe_unknown

        raise SimulationError(
            describe_unknown(
                "robot prefix", prefix, [r.prefix for r in self.robots], "prefixes are"
            )
        )

    # -- controllers --------------------------------------------------------------------------
    def control(
        self,
        controllers: str | os.PathLike[str] | ControllerConfig,
        *,
        prefix: str = "",
        context: Context | None = None,
        spawn: Sequence[str] | None = None,
        update_rate_hz: int | None = None,
        namespace: str | None = None,
        prepare: Callable[[ControllerManager], None] | None = None,
    ) -> ControlSystem:
        """Hardware + controller manager for the robot with ``prefix``, stepped with the physics
        (see :mod:`robomodel.sim.control_loop`: simulator plugins act on the MuJoCo state, mock
        hardware does not). ``prepare`` runs on the manager before its services are offered."""
        from robomodel.control.config import ControllerConfig, load_controller_config
        from robomodel.sim.control_loop import control_cycle, simulated_components

        built = self.robot(prefix)
        config = (
            controllers
            if isinstance(controllers, ControllerConfig)
            else load_controller_config(controllers)
        )
        components, simulated = simulated_components(built, self.model, self.data)
        self._hardware.extend(simulated)
        loop = control_cycle(
            built,
            config,
            components,
            timestep_s=self.timestep_s,
            context=context,
            spawn=spawn,
            update_rate_hz=update_rate_hz,
            namespace=namespace,
            prepare=prepare,
        )
        self._controls.append(loop.system)
        self._schedule.add(ScheduledCallback(loop.every_steps, loop.callback, 0))
        return loop.system

    def every(
        self,
        rate_hz: float,
        callback: StepCallback,
        *,
        order: int = 0,
        active: ActivePredicate | None = None,
    ) -> None:
        """Call ``callback(time_s)`` every ``1 / rate_hz`` of sim time (0: every step).

        Within a step, callbacks run by ``order`` (the bus tick -1, controller managers 0,
        sensors 1), then by registration. With ``active``, only while ``active()`` is True
        (asked at every due step: keep it cheap); an inactive callback does not break up the
        stretches MuJoCo steps in one call (:mod:`robomodel.sim.schedule`).
        """
        steps = 1 if rate_hz <= 0 else max(1, round(1.0 / (rate_hz * self.timestep_s)))
        self._schedule.add(ScheduledCallback(steps, callback, order, active))

    # -- stepping -------------------------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        """Advance ``n`` physics steps.

        Callbacks run at the steps they are due; the stretches between them go to MuJoCo in
        one ``mj_step(nstep=k)`` call (the same result as ``k`` single steps, without Python
        per step) unless a robot has position (kinematic) joints, which are written every step.

        Raises:
            DivergenceError: the state became NaN/infinite (checked every 100 steps and at the end).
        """
        self._advance(n)
        check_finite(self.model, self.data)

    def _advance(self, n: int) -> None:
        """``n`` steps, checking for divergence every 100 (see :meth:`step`)."""
        mj = mujoco()
        model, data = self.model, self.data
        schedule = self._schedule
        kinematic = [hw for hw in self._hardware if hw.has_kinematic_joints]
        mj_step = mj.mj_step
        steps = self._steps
        end = steps + n
        every_step = bool(kinematic) or schedule.runs_every_step
        while steps < end:
            schedule.run_due(steps, data.time)
            if every_step:  # something runs every step: no stretch to hand over
                for hw in kinematic:
                    hw.apply()
                mj_step(model, data)
                for hw in kinematic:  # position joints are kinematic: no drift within a step
                    hw.apply()
                steps += 1
            else:
                to_check = _CHECK_EVERY_STEPS - steps % _CHECK_EVERY_STEPS
                k = min(schedule.steps_to_next_due(steps), to_check, end - steps)
                mj_step(model, data, k)
                steps += k
            if steps % _CHECK_EVERY_STEPS == 0:
                self._steps = steps
                check_finite(model, data)
        self._steps = steps

    def run(
        self,
        duration_s: float,
        *,
        real_time_factor: float | None = None,
        until: Callable[[], bool] | None = None,
    ) -> float:
        """Run for ``duration_s`` of sim time; returns the wall time it took [s].

        Args:
            real_time_factor: ``None`` runs as fast as possible; 1.0 is real time, 2.0 twice
                as fast (the loop sleeps to keep pace, checked every 10 ms of sim time).
            until: Stop early when this returns True (checked every 10 ms of sim time).
        """
        total = max(0, round(duration_s / self.timestep_s))
        paced = until is not None or (real_time_factor is not None and real_time_factor > 0)
        chunk = max(1, round(0.01 / self.timestep_s)) if paced else max(1, total)
        start_wall = time.perf_counter()
        start_sim = self.time_s
        done = 0
        while done < total:
            n = min(chunk, total - done)
            self._advance(n)
            done += n
            if until is not None and until():
                break
            if real_time_factor is not None and real_time_factor > 0:
                target = start_wall + (self.time_s - start_sim) / real_time_factor
                delay = target - time.perf_counter()
                if delay > 0:
                    time.sleep(delay)
        self.check_finite()
        return time.perf_counter() - start_wall

    def check_finite(self) -> None:
        """Raise :class:`DivergenceError` if the physics state is not finite."""
        if self._data is not None:
            check_finite(self._model, self._data)

    # -- interaction ----------------------------------------------------------------------------
    def body_id(self, link: str, *, prefix: str = "") -> int:
        mj = mujoco()
        name = "world_link" if prefix + link == "world" else prefix + link
        bid = int(mj.mj_name2id(self.model, mj.mjtObj.mjOBJ_BODY, name))
        if bid < 0:
            from robomodel.errors import describe_unknown

            names = [self.model.body(i).name for i in range(self.model.nbody)]
            raise SimulationError(describe_unknown("unknown link", name, names, "bodies are"))
        return bid

    def apply_wrench(
        self,
        link: str,
        *,
        force_n: Sequence[float] = (0.0, 0.0, 0.0),
        torque_nm: Sequence[float] = (0.0, 0.0, 0.0),
        prefix: str = "",
    ) -> None:
        """Apply a force and torque (world frame, at the link's centre of mass) until changed.

        Like gazebo's ``apply_body_wrench`` without a duration; call again with zeros to stop.
        """
        values = np.asarray([*force_n, *torque_nm], dtype=float)
        if values.shape != (6,) or not np.isfinite(values).all():
            raise SimulationError(f"wrench must be 6 finite numbers, got {values.tolist()}")
        self.data.xfrc_applied[self.body_id(link, prefix=prefix)] = values

    def teleport(
        self,
        xyz_m: Sequence[float],
        rpy_rad: Sequence[float] = (0.0, 0.0, 0.0),
        *,
        prefix: str = "",
    ) -> None:
        """Move a robot's root to a pose, zeroing its velocity (``set_model_state``)."""
        from robomodel.description.rigid import quat_wxyz_from_rpy

        mj = mujoco()
        built = self.robot(prefix)
        pose = [float(v) for v in (*xyz_m, *rpy_rad)]
        if len(pose) != 6 or not all(math.isfinite(v) for v in pose):
            raise SimulationError(f"pose must be 6 finite numbers, got {pose}")
        bid = int(mj.mj_name2id(self.model, mj.mjtObj.mjOBJ_BODY, built.root_body))
        quat = quat_wxyz_from_rpy(*pose[3:])
        if built.floating:
            jid = int(self.model.body_jntadr[bid])
            qa, da = int(self.model.jnt_qposadr[jid]), int(self.model.jnt_dofadr[jid])
            self.data.qpos[qa : qa + 3] = pose[:3]
            self.data.qpos[qa + 3 : qa + 7] = quat
            self.data.qvel[da : da + 6] = 0.0
        else:
            self.model.body_pos[bid] = pose[:3]
            self.model.body_quat[bid] = quat
        mj.mj_forward(self.model, self.data)

    def reset(self) -> None:
        """Reset the world: initial state, time 0, no applied forces (``reset_world``)."""
        mj = mujoco()
        model, data = self.model, self.data
        mj.mj_resetData(model, data)
        if self._initial_qpos is not None:
            data.qpos[:] = self._initial_qpos
        mj.mj_forward(model, data)
        self._steps = 0
        for hw in self._hardware:
            hw.reset()
