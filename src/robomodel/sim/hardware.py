"""The simulated hardware component: gazebo_ros2_control's ``GazeboSystem`` on MuJoCo.

Per joint, the claimed command interface decides what the physics gets (gazebo_ros2_control
gazebo_system.cpp ``write``; ROS 1 default_robot_hw_sim.cpp ``writeSim``):

* ``position``: the joint is set to the command and its velocity to 0 before every physics
  step (Gazebo's ``SetPosition(0, cmd, true)``: kinematic, it ignores effort limits), clamped
  to the URDF limits as the joint-limits interface does;
* ``velocity``: a stiff MuJoCo velocity servo (force = kv (cmd - qdot), kv = 1e4 x the joint's
  inertia in 1/s, clamped to the URDF effort limit), as gazebo_ros_control's ODE joint motor
  with ``fmax`` = effort (a plain write of ``qvel`` before each step, like classic
  ``SetVelocity``, lets the light wheel absorb the contact impulse and the robot slips);
* ``effort``: the command, clamped to the URDF effort limit, is a generalised force
  (``SetForce``) held until the next write.

A command that is NaN or infinite (the value of an unclaimed interface, or a faulty controller)
is not applied: position and velocity joints hold still (``hold_joints``), effort joints get no
force; a faulty command is warned about once per joint. States: position ``qpos`` (continuous
joints unwrapped, as gazebo_ros_control accumulates), velocity ``qvel``, effort the applied
generalised force. The controller manager calls :meth:`read`/:meth:`write` at its update rate;
the engine calls :meth:`apply` every physics step (GZR2C writes every step).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

import numpy as np

from robomodel.control.hardware import (
    EFFORT,
    POSITION,
    VELOCITY,
    HardwareComponent,
    HardwareInfo,
    ReturnType,
)
from robomodel.sim._mujoco import mujoco
from robomodel.sim.build.robot import velocity_actuator_name
from robomodel.sim.exceptions import SimulationError

__all__ = ["MAX_POSITION_COMMAND", "MAX_VELOCITY_COMMAND", "SIMULATOR_PLUGINS", "SimSystem"]

# Largest commands passed to MuJoCo. It treats |value| > 1e10 (mjMAXVAL) in ctrl, qpos, qvel or
# qacc as a divergence ("Nan, Inf or huge value in CTRL") and resets; the velocity servo
# accelerates at 1e4 x the velocity error, so 1e4 rad/s (m/s) keeps even a step from rest
# below that. No motor comes near either bound.
MAX_VELOCITY_COMMAND = 1e4
MAX_POSITION_COMMAND = 1e9

SIMULATOR_PLUGINS = (
    "gazebo_ros2_control/GazeboSystem",
    "gz_ros2_control/GazeboSimSystem",
    "ign_ros2_control/IgnitionSystem",
)
_MODES = (POSITION, VELOCITY, EFFORT)
_OK = ReturnType.OK
# Velocity servo gain per unit of joint inertia [1/s]: a 0.1 ms time constant, stiff like ODE's
# joint motor; stable because implicitfast integrates the servo's damping implicitly.
_SERVO_GAIN = 1e4


class SimSystem(HardwareComponent):
    """Hardware whose joints are MuJoCo joints (see the module docstring).

    Args:
        info: The ``<ros2_control>`` block (or the one derived from ``<transmission>`` tags).
        model: The compiled ``mujoco.MjModel``.
        data: Its ``mujoco.MjData``.
        prefix: The robot's frame prefix (MuJoCo joint names are ``prefix + name``).
    """

    plugin_name = "gazebo_ros2_control/GazeboSystem"

    def __init__(self, info: HardwareInfo, model: Any, data: Any, *, prefix: str = "") -> None:
        super().__init__(info)
        self.model = model
        self.data = data
        # MjData's array properties build a new view on every access (about 1 us each): the
        # buffers never move, so keep the views.
        self._qpos, self._qvel = data.qpos, data.qvel
        self._qfrc, self._ctrl = data.qfrc_applied, data.ctrl
        # Scalar reads and writes through memoryviews of the same buffers return and take plain
        # Python floats without numpy's per-element boxing or fancy-index set-up (for a handful
        # of joints, cheaper than either whole-array tolist or index-array assignment).
        self._qpos_mv: Any = memoryview(self._qpos)  # format "d": items are Python floats
        self._qvel_mv: Any = memoryview(self._qvel)
        self._qfrc_mv: Any = memoryview(self._qfrc)
        self._ctrl_mv: Any = memoryview(self._ctrl)
        self._joints = [j.name for j in info.joints]
        self._qadr: list[int] = []
        self._dadr: list[int] = []
        ranges: list[tuple[float, float]] = []
        limits: list[float] = []
        servos: list[int] = []
        gains: list[float] = []
        for name in self._joints:
            jid = _joint_id(model, prefix + name, info.source)
            servos.append(_actuator_id(model, velocity_actuator_name(prefix + name)))
            dof = int(model.jnt_dofadr[jid])
            gains.append(_SERVO_GAIN * max(float(model.dof_M0[dof]), 1e-6))
            self._qadr.append(int(model.jnt_qposadr[jid]))
            self._dadr.append(int(model.jnt_dofadr[jid]))
            lo, hi = model.jnt_range[jid]
            ranges.append((lo, hi) if model.jnt_limited[jid] else (-math.inf, math.inf))
            effort = model.jnt_actfrcrange[jid][1] if model.jnt_actfrclimited[jid] else math.inf
            limits.append(float(effort))
        self._servo = servos
        self._servo_gain = gains
        self._range = np.array(ranges, dtype=float).reshape(-1, 2)
        self._effort_limit = np.array(limits, dtype=float)
        self._mode = [_first_mode(j.command_interfaces) for j in info.joints]
        self._warned: set[str] = set()
        self._hold_q = np.zeros(len(self._joints))
        self._slots: list[tuple[int, int, int, int]] = []  # (cmd, pos, vel, eff state) slots
        self._select()

    # -- interface ----------------------------------------------------------------------------
    def on_configure(self) -> None:
        self._slots = []
        for i, (name, mode) in enumerate(zip(self._joints, self._mode, strict=True)):
            cmd = self.command_slot(f"{name}/{mode}") if mode else -1
            self._slots.append(
                (
                    cmd,
                    self._state(f"{name}/{POSITION}"),
                    self._state(f"{name}/{VELOCITY}"),
                    self._state(f"{name}/{EFFORT}"),
                )
            )
            for d in self.info.joints[i].state_interfaces:  # GZR2C: initial_value sets the state
                if d.initial_value is not None and d.interface == POSITION:
                    self.data.qpos[self._qadr[i]] = d.initial_value
                elif d.initial_value is not None and d.interface == VELOCITY:
                    self.data.qvel[self._dadr[i]] = d.initial_value
        self.reset()
        self.read(0.0, 0.0)

    def _state(self, name: str) -> int:
        return self.state_slot(name) if self.has_state(name) else -1

    def perform_command_mode_switch(self, start: Sequence[str], stop: Sequence[str]) -> None:
        changed = False
        for iface in start:
            joint, _, mode = iface.rpartition("/")
            if joint in self._joints and mode in _MODES:
                self._mode[self._joints.index(joint)] = mode
                changed = True
        if changed and self._slots:
            self._slots = [
                (self.command_slot(f"{n}/{m}") if m else -1, sp, sv, se)
                for n, m, (_, sp, sv, se) in zip(self._joints, self._mode, self._slots, strict=True)
            ]
            self._select()

    def _select(self) -> None:
        """Per-mode index lists (plain lists and small int arrays: the loop runs at 1 kHz)."""
        q = np.array(self._qadr, dtype=int)
        d = np.array(self._dadr, dtype=int)
        groups = {m: [i for i, mode in enumerate(self._mode) if mode == m] for m in _MODES}
        self._pos_i, self._vel_i, self._eff_i = groups[POSITION], groups[VELOCITY], groups[EFFORT]
        slots = [s[0] for s in self._slots] if self._slots else [-1] * len(self._joints)
        self._pos_slots = [slots[i] for i in self._pos_i]
        self._vel_slots = [slots[i] for i in self._vel_i]
        self._eff_slots = [slots[i] for i in self._eff_i]
        self._pos_q, self._pos_d = q[self._pos_i], d[self._pos_i]
        self._eff_d = d[self._eff_i]
        self._eff_d_list = [self._dadr[i] for i in self._eff_i]
        self._pos_range = [tuple(self._range[i]) for i in self._pos_i]
        self._eff_limit = [float(self._effort_limit[i]) for i in self._eff_i]
        self._hold = [float(self._hold_q[i]) for i in self._pos_i]
        self._pos_cmd = np.array(self._hold, dtype=float)
        self._vel_act = np.array([self._servo[i] for i in self._vel_i], dtype=int)
        self._vel_act_list = [int(a) for a in self._vel_act]
        for i, actuator in enumerate(self._servo):
            if actuator >= 0:  # servo on for velocity-mode joints only
                kv = self._servo_gain[i] if i in self._vel_i else 0.0
                self.model.actuator_gainprm[actuator, 0] = kv
                self.model.actuator_biasprm[actuator, 2] = -kv
        if len(self._vel_act) and (self._vel_act < 0).any():
            raise SimulationError(
                f"hardware '{self.name}': a velocity-commanded joint has no velocity servo "
                "(mimic or planar joints cannot be commanded by velocity)",
                where=self.info.source,
            )
        self.data.ctrl[self._vel_act] = 0.0
        self._finite = [False] * len(self._joints)  # last command was finite (for warnings)
        self._ok = dict.fromkeys(_MODES, False)  # every command of the mode was finite
        # state reads: (slots, MuJoCo addresses) per kind
        self._read_p = [
            (s[1], a) for s, a in zip(self._slots, self._qadr, strict=False) if s[1] >= 0
        ]
        self._read_v = [
            (s[2], a) for s, a in zip(self._slots, self._dadr, strict=False) if s[2] >= 0
        ]
        self._read_e = [
            (s[3], a) for s, a in zip(self._slots, self._dadr, strict=False) if s[3] >= 0
        ]

    # -- the loop -------------------------------------------------------------------------------
    def read(self, time_s: float, period_s: float) -> ReturnType:
        states = self.states
        q = self._qpos_mv
        for slot, a in self._read_p:
            states[slot] = q[a]
        v = self._qvel_mv
        for slot, a in self._read_v:
            states[slot] = v[a]
        f = self._qfrc_mv
        for slot, a in self._read_e:
            states[slot] = f[a]
        return _OK

    def write(self, time_s: float, period_s: float) -> ReturnType:
        commands = self.commands
        if self._eff_slots:
            values = [commands[s] for s in self._eff_slots]
            if not math.isfinite(sum(values)):
                values = self._sanitize(values, self._eff_i, [0.0] * len(values), EFFORT)
            else:
                self._ok[EFFORT] = True
            qfrc = self._qfrc_mv
            for a, v, lim in zip(self._eff_d_list, values, self._eff_limit, strict=True):
                qfrc[a] = -lim if v < -lim else lim if v > lim else v
        if self._vel_slots:
            values = [commands[s] for s in self._vel_slots]
            if not math.isfinite(sum(values)):
                values = self._sanitize(values, self._vel_i, [0.0] * len(values), VELOCITY)
            else:
                self._ok[VELOCITY] = True
            if max(map(abs, values)) > MAX_VELOCITY_COMMAND:
                values = self._bounded(values, self._vel_i, VELOCITY, MAX_VELOCITY_COMMAND)
            ctrl = self._ctrl_mv
            for a, v in zip(self._vel_act_list, values, strict=True):
                ctrl[a] = v
        if self._pos_slots:
            values = [commands[s] for s in self._pos_slots]
            if not math.isfinite(sum(values)):
                values = self._sanitize(values, self._pos_i, self._hold, POSITION)
            else:
                self._ok[POSITION] = True
            values = [
                lo if v < lo else hi if v > hi else v
                for v, (lo, hi) in zip(values, self._pos_range, strict=True)
            ]
            if values and max(map(abs, values)) > MAX_POSITION_COMMAND:
                values = self._bounded(values, self._pos_i, POSITION, MAX_POSITION_COMMAND)
            self._hold = values
            self._pos_cmd[:] = values
        return _OK

    def _bounded(
        self, values: list[float], joints: list[int], mode: str, bound: float
    ) -> list[float]:
        """Clamp finite but huge commands to ``bound``, warning once per joint: MuJoCo would
        warn "Nan, Inf or huge value in CTRL/QPOS" and reset the simulation."""
        out = []
        for v, i in zip(values, joints, strict=True):
            if abs(v) > bound:
                key = f"huge:{self._joints[i]}"
                if key not in self._warned:
                    self._warned.add(key)
                    warnings.warn(
                        f"hardware '{self.name}': {mode} command {v:g} for joint "
                        f"'{self._joints[i]}' clamped to +-{bound:g}",
                        stacklevel=3,
                    )
                v = math.copysign(bound, v)
            out.append(v)
        return out

    def _sanitize(
        self, values: list[float], joints: list[int], fallback: list[float], mode: str
    ) -> list[float]:
        """Replace non-finite commands by ``fallback``, warning once per joint whose command
        was finite before (unclaimed interfaces are NaN from the start: no warning)."""
        all_were_finite = self._ok[mode]
        self._ok[mode] = False
        out = []
        for k, (value, i) in enumerate(zip(values, joints, strict=True)):
            if math.isfinite(value):
                self._finite[i] = True
                out.append(value)
                continue
            if (self._finite[i] or all_were_finite) and self._joints[i] not in self._warned:
                self._warn_bad(i, value)
            self._finite[i] = False
            out.append(fallback[k])
        return out

    def _warn_bad(self, i: int, value: float) -> None:
        self._warned.add(self._joints[i])
        warnings.warn(
            f"hardware '{self.name}': joint '{self._joints[i]}' got a {value} "
            f"{self._mode[i]} command; not applied (the joint holds)",
            stacklevel=3,
        )

    @property
    def has_kinematic_joints(self) -> bool:
        """Position joints (written into the state every physics step)."""
        return bool(self._pos_i)

    def apply(self) -> None:
        """Write the kinematic (position) commands into the state; every physics step."""
        if self._pos_i:
            self._qpos[self._pos_q] = self._pos_cmd
            self._qvel[self._pos_d] = 0.0

    def reset(self) -> None:
        """Hold the current positions and forget the commands (start, world reset)."""
        self._hold_q = self.data.qpos[self._qadr].copy()
        self._select()
        self.data.qfrc_applied[self._eff_d] = 0.0


def _first_mode(interfaces: Sequence[Any]) -> str:
    for d in interfaces:
        if d.interface in _MODES:
            return str(d.interface)
    return ""


def _actuator_id(model: Any, name: str) -> int:
    mj = mujoco()
    return int(mj.mj_name2id(model, mj.mjtObj.mjOBJ_ACTUATOR, name))


def _joint_id(model: Any, name: str, where: str) -> int:
    mj = mujoco()
    jid = int(mj.mj_name2id(model, mj.mjtObj.mjOBJ_JOINT, name))
    if jid < 0:
        raise SimulationError(f"hardware joint '{name}' is not a simulated joint", where=where)
    return jid
