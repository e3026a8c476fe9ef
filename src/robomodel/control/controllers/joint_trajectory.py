"""joint_trajectory_controller (ros2_controllers, humble behaviour).

Trajectories arrive on ``~/joint_trajectory`` (ROS 1 mapping: ``~/command``) or through
:meth:`JointTrajectoryController.send_goal` (the FollowJointTrajectory action's semantics,
in-process). A new trajectory replaces the running one (humble: "just forgets the old
trajectory"); a running goal is then canceled. Tolerances (``constraints``) abort with
``PATH_TOLERANCE_VIOLATED`` or ``GOAL_TOLERANCE_VIOLATED`` and hold the measured position.
Position commands forward the desired position; velocity/effort-only commands run a PID per
joint on the position error with the velocity error as its derivative (``gains.<joint>``).

Goals and trajectory validation live in :mod:`.joint_trajectory_goal`; tolerance checks in
:mod:`.joint_trajectory_tolerances`; sampling in :mod:`.trajectory`. The action, the services
and the state topics (:mod:`.joint_trajectory_services`) read the controller through
:meth:`JointTrajectoryController.snapshot` only.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from types import MappingProxyType
from typing import Any

from robomodel.control.controllers.base import (
    ControllerInterface,
    InterfaceConfiguration,
    ReturnType,
)
from robomodel.control.controllers.exceptions import ControllerError
from robomodel.control.controllers.joint_trajectory_goal import (
    GoalHandle,
    GoalStatus,
    validate_trajectory,
)
from robomodel.control.controllers.joint_trajectory_services import TrajectoryControllerBus
from robomodel.control.controllers.joint_trajectory_snapshot import TrajectoryControllerSnapshot
from robomodel.control.controllers.joint_trajectory_tolerances import (
    goal_reached,
    goal_time_s,
    path_violation,
    position_errors,
)
from robomodel.control.controllers.trajectory import Sample, Trajectory, TrajectoryPoint
from robomodel.control.pid import Gains, Pid
from robomodel.runtime.msg import JointTrajectory

__all__ = ["GoalHandle", "GoalStatus", "JointTrajectoryController"]

log = logging.getLogger("robomodel.control")

_ALLOWED_COMMANDS = (
    ("position",),
    ("position", "velocity"),
    ("position", "velocity", "acceleration"),
    ("velocity",),
    ("effort",),
    ("position", "effort"),
)


class JointTrajectoryController(ControllerInterface):
    """``joint_trajectory_controller/JointTrajectoryController`` (see the module docstring)."""

    type_name = "joint_trajectory_controller/JointTrajectoryController"

    def on_init(self) -> None:
        self.joints = self.param_list("joints", [])
        if not self.joints:
            raise ControllerError(f"controller '{self.name}': 'joints' parameter is empty")
        self.command_kinds = tuple(self.param_list("command_interfaces", []))
        self.state_kinds = tuple(self.param_list("state_interfaces", []))
        if self.command_kinds not in _ALLOWED_COMMANDS:
            raise ControllerError(
                f"controller '{self.name}': command_interfaces {list(self.command_kinds)} are "
                f"not a supported combination; use one of {[list(c) for c in _ALLOWED_COMMANDS]}"
            )
        if "position" not in self.state_kinds:
            raise ControllerError(f"controller '{self.name}': state_interfaces need 'position'")
        self.use_pid = "position" not in self.command_kinds
        if self.use_pid and "velocity" not in self.state_kinds:
            raise ControllerError(
                f"controller '{self.name}': velocity/effort commands need position and velocity states"
            )
        self.allow_partial_joints_goal = bool(self.param("allow_partial_joints_goal", False))
        self.allow_nonzero_velocity_at_trajectory_end = bool(
            self.param("allow_nonzero_velocity_at_trajectory_end", True)  # humble default
        )
        self.stopped_velocity_tolerance = self.param_float(
            "constraints.stopped_velocity_tolerance", 0.01
        )
        self.goal_time_s = self.param_float("constraints.goal_time", 0.0)
        self.path_tolerance = {
            j: self.param_float(f"constraints.{j}.trajectory", 0.0) for j in self.joints
        }
        self.goal_tolerance = {
            j: self.param_float(f"constraints.{j}.goal", 0.0) for j in self.joints
        }
        self.topic = str(self.param("topic", "~/joint_trajectory"))
        self.pids = [Pid(Gains.from_params({"p": 0.0, **self._gains(j)})) for j in self.joints]
        self.ff_velocity_scale = [
            float(self.params.get(f"gains.{j}.ff_velocity_scale", 0.0)) for j in self.joints
        ]
        self.wraparound = [
            bool(self.params.get(f"gains.{j}.angle_wraparound", False))
            or bool(self.params.get(f"gains.{j}.normalize_error", False))  # humble, deprecated
            for j in self.joints
        ]
        self.cmd_timeout_s = self.param_float("cmd_timeout", 0.0)
        # Jazzy publishes the state at every update; Humble's state_publish_rate, if a
        # controller YAML still sets it, throttles it
        self.state_publish_rate_hz = self.param_float("state_publish_rate", 0.0)
        self._bus: TrajectoryControllerBus | None = None
        self._next_state_s = -math.inf
        self._active = False
        self._now_s = 0.0
        self._cmd: dict[str, Sequence[Any]] = {}
        self._state: dict[str, Sequence[Any]] = {}
        self.trajectory: Trajectory | None = None
        self.goal: GoalHandle | None = None
        self._pending: tuple[JointTrajectory, GoalHandle | None] | None = None
        self._holding = True

    def _gains(self, joint: str) -> dict[str, Any]:
        prefix = f"gains.{joint}."
        return {k[len(prefix) :]: v for k, v in self.params.items() if k.startswith(prefix)}

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual(
            [f"{j}/{k}" for k in self.command_kinds for j in self.joints]
        )

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual(
            [f"{j}/{k}" for k in self.state_kinds for j in self.joints]
        )

    def on_configure(self) -> None:
        if self.node is not None:
            self._sub = self.node.create_subscription(
                JointTrajectory, self.topic, self._on_trajectory, 10
            )
            # FollowJointTrajectory (a ROS 2 action), QueryTrajectoryState, controller_state
            self._bus = TrajectoryControllerBus(self.node, self)

    def on_cleanup(self) -> None:
        sub = getattr(self, "_sub", None)
        if sub is not None:
            sub.destroy()
            del self._sub
        if self._bus is not None:
            self._bus.destroy()
        self._bus = None

    def cancel_goal(self, handle: GoalHandle) -> None:
        """Cancel a running goal: the controller holds the measured position."""
        if handle is self.goal and handle.status is GoalStatus.ACTIVE:
            self._finish(GoalStatus.CANCELED, 0, "canceled")
            self._hold(self._now_s)
        elif self._pending is not None and self._pending[1] is handle:
            self._pending = None
            handle.status = GoalStatus.CANCELED

    def on_activate(self) -> None:
        n = len(self.joints)
        self._cmd = {
            k: self.command_interfaces[i * n : (i + 1) * n]
            for i, k in enumerate(self.command_kinds)
        }
        self._state = {
            k: self.state_interfaces[i * n : (i + 1) * n] for i, k in enumerate(self.state_kinds)
        }
        for pid in self.pids:
            pid.reset()
        self._now_s = 0.0
        self._hold(0.0)
        self._active = True

    def on_deactivate(self) -> None:
        self._active = False
        if self.goal is not None and self.goal.status is GoalStatus.ACTIVE:
            self._finish(GoalStatus.ABORTED, -1, "controller deactivated")
        self.trajectory = None

    # -- inputs ---------------------------------------------------------------------------------
    def _measured(self, kind: str) -> tuple[float, ...]:
        return tuple(si.get() for si in self._state.get(kind, ()))

    def snapshot(self) -> TrajectoryControllerSnapshot:
        """The controller's state as of its last update: what its action and services read
        (measured values and commands only while active: the interfaces are loaned then)."""
        if not self._active:
            return TrajectoryControllerSnapshot(
                self._now_s,
                False,
                tuple(self.joints),
                (),
                (),
                self.trajectory,
                self.goal,
                MappingProxyType({}),
            )
        return self._snapshot(self._measured("position"), self._measured("velocity"))

    def _snapshot(
        self, positions: Sequence[float], velocities: Sequence[float]
    ) -> TrajectoryControllerSnapshot:
        return TrajectoryControllerSnapshot(
            time_s=self._now_s,
            active=self._active,
            joints=tuple(self.joints),
            positions=tuple(positions),
            velocities=tuple(velocities),
            trajectory=self.trajectory,
            goal=self.goal,
            commands=MappingProxyType(
                {kind: tuple(ci.get() for ci in cis) for kind, cis in self._cmd.items()}
            ),
        )

    def validate(self, msg: JointTrajectory) -> str:
        """Why ``msg`` is rejected (humble ``validate_trajectory_msg``), or ``""``."""
        return validate_trajectory(
            msg,
            joints=self.joints,
            allow_partial_joints_goal=self.allow_partial_joints_goal,
            allow_nonzero_velocity_at_trajectory_end=self.allow_nonzero_velocity_at_trajectory_end,
            now_s=self._now_s,
        )

    def _on_trajectory(self, msg: JointTrajectory) -> None:
        self.send_trajectory(msg)

    def send_trajectory(self, msg: JointTrajectory) -> bool:
        """Take a trajectory as the topic does; False (and a warning) when rejected."""
        reason = self.validate(msg)
        if reason:
            log.warning("%s: trajectory rejected: %s", self.name, reason)
            return False
        self._pending = (msg, None)
        return True

    def send_goal(
        self,
        msg: JointTrajectory,
        *,
        path_tolerance: dict[str, float] | None = None,
        goal_tolerance: dict[str, float] | None = None,
        goal_time_tolerance_s: float | None = None,
    ) -> GoalHandle:
        """A FollowJointTrajectory goal; tolerances override per joint (>0 use, -1 erase)."""
        handle = GoalHandle(
            path_tolerance=dict(path_tolerance or {}),
            goal_tolerance=dict(goal_tolerance or {}),
            goal_time_tolerance_s=goal_time_tolerance_s,
        )
        reason = self.validate(msg)
        if reason:
            handle.status, handle.error_code, handle.error_string = GoalStatus.ABORTED, -1, reason
            return handle
        self._pending = (msg, handle)
        return handle

    def _start(self, msg: JointTrajectory, handle: GoalHandle | None, now: float) -> None:
        if self.goal is not None and self.goal.status is GoalStatus.ACTIVE:
            # humble preempt_active_goal: canceled with INVALID_GOAL
            self._finish(
                GoalStatus.CANCELED, -1, "Current goal cancelled due to new incoming action."
            )
        index = [self.joints.index(j) for j in msg.joint_names]
        pos_now = list(self._measured("position"))
        full_points = []
        for point in msg.points:
            positions = list(pos_now)
            for k, i in enumerate(index):
                positions[i] = point.positions[k]
            vel: tuple[float, ...] = ()
            acc: tuple[float, ...] = ()
            if point.velocities:
                v = [0.0] * len(self.joints)
                for k, i in enumerate(index):
                    v[i] = point.velocities[k]
                vel = tuple(v)
            if point.accelerations:
                a = [0.0] * len(self.joints)
                for k, i in enumerate(index):
                    a[i] = point.accelerations[k]
                acc = tuple(a)
            t = point.time_from_start.sec + point.time_from_start.nanosec * 1e-9
            full_points.append(TrajectoryPoint(t, tuple(positions), vel, acc))
        stamp = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
        velocities = self._measured("velocity")
        before = TrajectoryPoint(0.0, tuple(pos_now), velocities)
        self.trajectory = Trajectory(stamp if stamp != 0.0 else now, full_points, now, before)
        self.goal = handle
        self._holding = False

    def _finish(self, status: GoalStatus, code: int, text: str) -> None:
        if self.goal is not None:
            self.goal.status, self.goal.error_code, self.goal.error_string = status, code, text
            self.goal = None

    def _hold(self, now: float) -> None:
        """set_hold_position: a one-point trajectory at the measured position."""
        pos = self._measured("position")
        self.trajectory = Trajectory(
            now, [TrajectoryPoint(0.0, pos)], now, TrajectoryPoint(0.0, pos)
        )
        self._holding = True

    # -- the cycle ------------------------------------------------------------------------------
    def update(self, time_s: float, period_s: float) -> ReturnType:
        self._now_s = time_s
        if self._pending is not None:
            msg, handle = self._pending
            self._pending = None
            self._start(msg, handle, time_s)
        traj = self.trajectory
        if traj is None:
            return ReturnType.OK
        sample = traj.sample(time_s)
        if sample is None:
            return ReturnType.OK
        pos = self._measured("position")
        vel = self._measured("velocity")
        errors = position_errors(sample.positions, pos, self.wraparound)
        if (
            self.cmd_timeout_s > 0.0
            and not self._holding
            and time_s - traj.end_s > self.cmd_timeout_s
        ):
            self._hold(time_s)  # humble: after the end + cmd_timeout, hold position
            return self.update(time_s, period_s)
        if not self._holding and self._aborted_on_tolerance(time_s, traj, sample, errors, vel):
            return self.update(time_s, period_s)  # now holding the measured position
        self._write(
            sample.positions, sample.velocities, sample.accelerations, errors, vel, period_s
        )
        self._publish_state_when_due(time_s, sample, pos, vel, errors)
        return ReturnType.OK

    def _aborted_on_tolerance(
        self,
        time_s: float,
        traj: Trajectory,
        sample: Sample,
        errors: Sequence[float],
        vel: Sequence[float],
    ) -> bool:
        """Check the path tolerances before the trajectory's end and the goal tolerances after
        (humble ``update``); True when the goal was aborted and the controller holds."""
        goal = self.goal
        if sample.segment < len(traj.points):
            overrides = goal.path_tolerance if goal else {}
            joint = path_violation(self.joints, self.path_tolerance, overrides, errors)
            if joint is None:
                return False
            log.warning("%s: path tolerance violated on %s", self.name, joint)
            self._finish(GoalStatus.ABORTED, -4, f"path tolerance violated on {joint}")
            self._hold(time_s)
            return True
        overrides = goal.goal_tolerance if goal else {}
        reached = goal_reached(
            self.joints,
            self.goal_tolerance,
            overrides,
            errors,
            self.stopped_velocity_tolerance,
            sample.velocities,
            vel,
        )
        if reached:
            self._finish(GoalStatus.SUCCEEDED, 0, "")
            self._holding = True  # set_success_trajectory_point: keep the last waypoint
            return False
        goal_time = goal_time_s(self.goal_time_s, goal)
        if goal_time > 0.0 and time_s - traj.end_s > goal_time:
            log.warning("%s: goal tolerance violated", self.name)
            self._finish(GoalStatus.ABORTED, -5, "goal tolerance violated")
            self._hold(time_s)
            return True
        return False

    def _publish_state_when_due(
        self,
        time_s: float,
        sample: Sample,
        pos: Sequence[float],
        vel: Sequence[float],
        errors: Sequence[float],
    ) -> None:
        """Publish ``~/controller_state`` every update, or at ``state_publish_rate``."""
        if self._bus is not None and time_s + 1e-9 >= self._next_state_s:  # ns tolerance
            if self.state_publish_rate_hz > 0.0:
                self._next_state_s = time_s + 1.0 / self.state_publish_rate_hz
            self._bus.publish_state(self._snapshot(pos, vel), sample, errors)

    def _write(
        self,
        p: Sequence[float],
        v: Sequence[float],
        a: Sequence[float],
        errors: Sequence[float],
        vel: Sequence[float],
        period_s: float,
    ) -> None:
        cmd = self._cmd
        if "position" in cmd:
            for ci, x in zip(cmd["position"], p, strict=True):
                ci.set(x)
            if "velocity" in cmd:
                for ci, x in zip(cmd["velocity"], v, strict=True):
                    ci.set(x)
            if "acceleration" in cmd:
                for ci, x in zip(cmd["acceleration"], a, strict=True):
                    ci.set(x)
            return
        kind = "velocity" if "velocity" in cmd else "effort"
        for i, ci in enumerate(cmd[kind]):
            vel_error = v[i] - (vel[i] if vel else 0.0)
            u = self.ff_velocity_scale[i] * v[i] + self.pids[i].compute_with_rate(
                errors[i], vel_error, period_s
            )
            ci.set(u)
