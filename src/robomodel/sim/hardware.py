"""The simulated hardware component: gazebo_ros2_control's ``GazeboSystem`` on MuJoCo.

Per joint, the claimed command interface decides what the physics gets (gazebo_ros2_control
gazebo_system.cpp ``write``; ROS 1 default_robot_hw_sim.cpp ``writeSim``):

* ``position``: the joint is set to the command and its velocity to 0 before every physics
  step (Gazebo's ``SetPosition(0, cmd, true)``: kinematic, it ignores effort limits), clamped
  to the URDF limits as the joint-limits interface does;
* ``velocity``: the joint velocity is set before every physics step (``SetVelocity``);
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
from robomodel.sim.exceptions import SimulationError

__all__ = ["SIMULATOR_PLUGINS", "SimSystem"]

SIMULATOR_PLUGINS = (
    "gazebo_ros2_control/GazeboSystem",
    "gz_ros2_control/GazeboSimSystem",
    "ign_ros2_control/IgnitionSystem",
)
_MODES = (POSITION, VELOCITY, EFFORT)
_OK = ReturnType.OK


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
        self._joints = [j.name for j in info.joints]
        self._qadr: list[int] = []
        self._dadr: list[int] = []
        ranges: list[tuple[float, float]] = []
        limits: list[float] = []
        for name in self._joints:
            jid = _joint_id(model, prefix + name, info.source)
            self._qadr.append(int(model.jnt_qposadr[jid]))
            self._dadr.append(int(model.jnt_dofadr[jid]))
            lo, hi = model.jnt_range[jid]
            ranges.append((lo, hi) if model.jnt_limited[jid] else (-math.inf, math.inf))
            effort = model.jnt_actfrcrange[jid][1] if model.jnt_actfrclimited[jid] else math.inf
            limits.append(float(effort))
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
        idx = {m: [i for i, mode in enumerate(self._mode) if mode == m] for m in _MODES}
        self._pos_i = np.array(idx[POSITION], dtype=int)
        self._vel_i = np.array(idx[VELOCITY], dtype=int)
        self._eff_i = np.array(idx[EFFORT], dtype=int)
        q = np.array(self._qadr, dtype=int)
        d = np.array(self._dadr, dtype=int)
        self._pos_q, self._pos_d = q[self._pos_i], d[self._pos_i]
        self._vel_d, self._eff_d = d[self._vel_i], d[self._eff_i]
        self._cmd = np.full(len(self._joints), math.nan)
        self._pos_cmd = self._hold_q[self._pos_i].copy()
        self._vel_cmd = np.zeros(len(self._vel_i))

    # -- the loop -------------------------------------------------------------------------------
    def read(self, time_s: float, period_s: float) -> ReturnType:
        qpos, qvel = self.data.qpos, self.data.qvel
        force = self.data.qfrc_applied
        states = self.states
        for (_, sp, sv, se), qa, da in zip(self._slots, self._qadr, self._dadr, strict=True):
            if sp >= 0:
                states[sp] = float(qpos[qa])
            if sv >= 0:
                states[sv] = float(qvel[da])
            if se >= 0:
                states[se] = float(force[da])
        return _OK

    def write(self, time_s: float, period_s: float) -> ReturnType:
        commands = self.commands
        cmd = self._cmd
        for i, (slot, *_) in enumerate(self._slots):
            value = commands[slot] if slot >= 0 else math.nan
            if not math.isfinite(value):
                if slot >= 0 and not math.isnan(cmd[i]) and self._joints[i] not in self._warned:
                    self._warn_bad(i, value)
                value = math.nan
            cmd[i] = value
        for i in self._pos_i:
            if math.isnan(cmd[i]):
                cmd[i] = self._hold_q[i]
            else:
                lo, hi = self._range[i]
                cmd[i] = min(max(cmd[i], lo), hi)
                self._hold_q[i] = cmd[i]
        for i in self._vel_i:
            if math.isnan(cmd[i]):
                cmd[i] = 0.0
        force = self.data.qfrc_applied
        for i, d in zip(self._eff_i, self._eff_d, strict=True):
            value = 0.0 if math.isnan(cmd[i]) else cmd[i]
            limit = self._effort_limit[i]
            force[d] = min(max(value, -limit), limit)
        self._pos_cmd = cmd[self._pos_i]
        self._vel_cmd = cmd[self._vel_i]
        return _OK

    def _warn_bad(self, i: int, value: float) -> None:
        self._warned.add(self._joints[i])
        warnings.warn(
            f"hardware '{self.name}': joint '{self._joints[i]}' got a {value} "
            f"{self._mode[i]} command; not applied (the joint holds)",
            stacklevel=3,
        )

    @property
    def has_position_joints(self) -> bool:
        return len(self._pos_q) > 0

    def apply(self) -> None:
        """Write the kinematic (position/velocity) commands into the state; every physics step."""
        if len(self._pos_q):
            self.data.qpos[self._pos_q] = self._pos_cmd
            self.data.qvel[self._pos_d] = 0.0
        if len(self._vel_d):
            self.data.qvel[self._vel_d] = self._vel_cmd

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


def _joint_id(model: Any, name: str, where: str) -> int:
    mj = mujoco()
    jid = int(mj.mj_name2id(model, mj.mjtObj.mjOBJ_JOINT, name))
    if jid < 0:
        raise SimulationError(f"hardware joint '{name}' is not a simulated joint", where=where)
    return jid
