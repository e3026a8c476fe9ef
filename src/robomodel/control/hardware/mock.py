"""``mock_components/GenericSystem``: hardware whose state follows its commands.

Follows ros2_control hardware_interface/src/mock_components/generic_system.cpp (``read``):
without ``calculate_dynamics`` a finite position command becomes the position state (plus
``position_state_following_offset``) and every other state with a same-named command mirrors
it; with ``calculate_dynamics`` each joint integrates its command mode (position, velocity or
acceleration). Mimic joints follow their source.

robomodel extension, for effort-commanded joints (no upstream equivalent: upstream rejects
them with ``calculate_dynamics``): when the component is given the robot's
:class:`~robomodel.kinematics.Dynamics` and ``calculate_dynamics`` is true, joints whose only
command interface is ``effort`` are integrated as a rigid body (``M q̈ = τ − C q̇ − g − b q̇``,
semi-implicit Euler with sub-steps of at most ``effort_substep_s``, default 1 ms, the
mass matrix evaluated once per period), so an effort
PID moves the arm without a simulator. The simulator replaces this with MuJoCo.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from robomodel.control.hardware.base import HardwareComponent, HardwareInfo, ReturnType
from robomodel.control.hardware.exceptions import HardwareError
from robomodel.control.hardware.interfaces import (
    ACCELERATION,
    EFFORT,
    POSITION,
    VELOCITY,
    InterfaceDescription,
)

if TYPE_CHECKING:
    from robomodel.kinematics.dynamics import Dynamics

__all__ = ["GenericSystem"]

_BOOL_TRUE = ("true", "1", "yes", "on")


def _flag(params: Mapping[str, str], name: str) -> bool:
    return str(params.get(name, "false")).strip().lower() in _BOOL_TRUE


def _number(params: Mapping[str, str], name: str, default: float) -> float:
    text = params.get(name)
    if text is None or str(text).strip() == "":
        return default
    try:
        return float(text)
    except ValueError:
        raise HardwareError(f"hardware parameter '{name}' must be a number, got {text!r}") from None


@dataclass(slots=True)
class _Joint:
    name: str
    sp: int  # state slots (-1 when absent)
    sv: int
    sa: int
    se: int
    cp: int  # command slots
    cv: int
    ca: int
    ce: int
    mode: str = POSITION


class GenericSystem(HardwareComponent):
    """Mock hardware (see the module docstring).

    Hardware parameters: ``mock_sensor_commands``, ``mock_gpio_commands``, ``disable_commands``,
    ``calculate_dynamics``, ``position_state_following_offset``,
    ``custom_interface_with_following_offset`` (all as upstream), ``effort_substep_s``.

    Args:
        info: The component description.
        mimic: Mimic joints of this component: name -> (source, multiplier, offset).
        dynamics: Rigid-body model for effort-commanded joints (robomodel extension).
        damping: Viscous damping per joint [N·m·s/rad] for that integration (URDF ``<dynamics>``).
    """

    plugin_name = "mock_components/GenericSystem"

    def __init__(
        self,
        info: HardwareInfo,
        *,
        mimic: Mapping[str, tuple[str, float, float]] | None = None,
        dynamics: Dynamics | None = None,
        damping: Mapping[str, float] | None = None,
    ) -> None:
        super().__init__(info)
        p = info.params
        self.mock_sensor_commands = _flag(p, "mock_sensor_commands")
        self.mock_gpio_commands = _flag(p, "mock_gpio_commands")
        self.disable_commands = _flag(p, "disable_commands")
        self.calculate_dynamics = _flag(p, "calculate_dynamics")
        self.offset = _number(p, "position_state_following_offset", 0.0)
        self.custom_offset_interface = str(p.get("custom_interface_with_following_offset", ""))
        self.effort_substep_s = _number(p, "effort_substep_s", 1e-3)
        self._mimic_spec = dict(mimic or {})
        self._dynamics = dynamics
        self._damping = dict(damping or {})
        self._joints: list[_Joint] = []
        self._mirror: list[tuple[int, int]] = []
        self._mimic: list[tuple[_Joint, _Joint, float, float]] = []
        self._effort_joints: list[tuple[_Joint, int]] = []
        for joint in info.joints:
            if joint.name in self._mimic_spec and joint.command_interfaces:
                raise HardwareError(
                    f"{info.source or info.name}: mimic joint '{joint.name}' may not have "
                    "command interfaces (ros2_control component_parser)"
                )

    def export_command_interfaces(self) -> list[InterfaceDescription]:
        exported = super().export_command_interfaces()
        names = {d.name for d in exported}
        extra = []
        groups = (self.info.sensors if self.mock_sensor_commands else ()) + (
            self.info.gpios if self.mock_gpio_commands else ()
        )
        for comp in groups:  # export_unlisted_command_interface_descriptions
            for d in comp.state_interfaces:
                if d.name not in names:
                    extra.append(d)
        return exported + extra

    def _slot(self, kind: str, name: str) -> int:
        if kind == "s":
            return self.state_slot(name) if self.has_state(name) else -1
        return self.command_slot(name) if self.has_command(name) else -1

    def on_configure(self) -> None:
        self._joints = []
        for comp in self.info.joints:
            n = comp.name
            st = [self._slot("s", f"{n}/{i}") for i in (POSITION, VELOCITY, ACCELERATION, EFFORT)]
            cm = [self._slot("c", f"{n}/{i}") for i in (POSITION, VELOCITY, ACCELERATION, EFFORT)]
            j = _Joint(n, st[0], st[1], st[2], st[3], cm[0], cm[1], cm[2], cm[3])
            commanded = {d.interface for d in comp.command_interfaces}
            if commanded == {EFFORT}:
                j.mode = EFFORT
            elif POSITION not in commanded and VELOCITY in commanded:
                j.mode = VELOCITY
            elif POSITION not in commanded and ACCELERATION in commanded:
                j.mode = ACCELERATION
            self._joints.append(j)
            for d in comp.state_interfaces:  # NaN states without initial value start at 0
                slot = self.state_slot(d.name)
                if d.data_type in ("double", "float32") and math.isnan(self.states[slot]):
                    self.states[slot] = 0.0
                if d.interface == POSITION and not self.custom_offset_interface:
                    self.states[slot] += self.offset
        by_name = {j.name: j for j in self._joints}
        self._mimic = [
            (by_name[name], by_name[src], mult, off)
            for name, (src, mult, off) in self._mimic_spec.items()
            if name in by_name and src in by_name
        ]
        self._custom: list[tuple[int, int]] = []
        if self.custom_offset_interface:
            for j, comp in zip(self._joints, self.info.joints, strict=True):
                name = f"{comp.name}/{self.custom_offset_interface}"
                if j.cp >= 0 and self.has_state(name):
                    self._custom.append((self.state_slot(name), j.cp))
        # loopback starts after position (index 1) or, with dynamics, after acceleration (3)
        position_handled = (
            {POSITION, VELOCITY, ACCELERATION} if self.calculate_dynamics else {POSITION}
        )
        self._mirror = []
        groups = list(self.info.joints)
        if self.mock_sensor_commands:
            groups += self.info.sensors
        groups += self.info.gpios
        for comp in groups:
            for d in comp.state_interfaces:
                if comp in self.info.joints and d.interface in position_handled:
                    continue
                if self.has_command(d.name):
                    self._mirror.append((self.state_slot(d.name), self.command_slot(d.name)))
        self._effort_joints = []
        if self._dynamics is not None and self.calculate_dynamics:
            names = self._dynamics.model.joint_names
            for j in self._joints:
                if j.mode == EFFORT and j.name in names:
                    self._effort_joints.append((j, names.index(j.name)))

    def perform_command_mode_switch(self, start: Sequence[str], stop: Sequence[str]) -> None:
        if not self.calculate_dynamics:
            return
        for name in start:
            prefix, _, iface = name.rpartition("/")
            for j in self._joints:
                if j.name == prefix and iface in (POSITION, VELOCITY, ACCELERATION, EFFORT):
                    j.mode = iface

    def prepare_command_mode_switch(self, start: Sequence[str], stop: Sequence[str]) -> bool:
        if not self.calculate_dynamics:
            return True
        per_joint: dict[str, int] = {}
        for name in start:
            prefix, _, iface = name.rpartition("/")
            if iface in (POSITION, VELOCITY, ACCELERATION):
                per_joint[prefix] = per_joint.get(prefix, 0) + 1
        return all(count == 1 for count in per_joint.values())

    # -- the loop ---------------------------------------------------------------------------
    def read(self, time_s: float, period_s: float) -> ReturnType:
        if self.disable_commands:
            return ReturnType.OK
        s, c = self.states, self.commands
        isfinite = math.isfinite
        if not self.calculate_dynamics:
            # with a custom following interface the offset goes there, not to the position
            off = 0.0 if self._custom else self.offset
            for j in self._joints:
                if j.cp >= 0 and j.sp >= 0:
                    v = c[j.cp]
                    if isfinite(v):
                        s[j.sp] = v + off
            for state_slot, command_slot in self._custom:
                if isfinite(c[command_slot]):
                    s[state_slot] = c[command_slot] + self.offset
        else:
            self._integrate(period_s)
        for state_slot, command_slot in self._mirror:
            v = c[command_slot]
            if isfinite(v):
                s[state_slot] = v
            elif v == v:  # inf: upstream returns ERROR
                return ReturnType.ERROR
        for j, src, mult, off in self._mimic:
            if j.sp >= 0 and src.sp >= 0:
                s[j.sp] = off + mult * s[src.sp]
            if j.sv >= 0 and src.sv >= 0:
                s[j.sv] = mult * s[src.sv]
            if j.sa >= 0 and src.sa >= 0:
                s[j.sa] = mult * s[src.sa]
        return ReturnType.OK

    def _integrate(self, dt: float) -> None:
        s, c = self.states, self.commands
        for j in self._joints:
            if j.mode == EFFORT:
                continue
            p_old = s[j.sp] if j.sp >= 0 else 0.0
            v_old = s[j.sv] if j.sv >= 0 else 0.0
            if j.mode == ACCELERATION and j.ca >= 0 and math.isfinite(c[j.ca]):
                a = c[j.ca]
                v = v_old + a * dt
                p = p_old + v * dt
            elif j.mode == VELOCITY and j.cv >= 0 and math.isfinite(c[j.cv]):
                v = c[j.cv]
                a = (v - v_old) / dt if dt > 0 else 0.0
                p = p_old + v * dt
            elif j.mode == POSITION and j.cp >= 0 and math.isfinite(c[j.cp]):
                p = c[j.cp] + self.offset
                v = (p - p_old) / dt if dt > 0 else 0.0
                a = (v - v_old) / dt if dt > 0 else 0.0
            else:
                continue
            if j.sp >= 0:
                s[j.sp] = p
            if j.sv >= 0:
                s[j.sv] = v
            if j.sa >= 0:
                s[j.sa] = a
        if self._effort_joints and dt > 0:
            self._integrate_effort(dt)

    def _integrate_effort(self, dt: float) -> None:
        dyn = self._dynamics
        assert dyn is not None  # only called when set
        s, c = self.states, self.commands
        q = np.zeros(dyn.n_v)
        v = np.zeros(dyn.n_v)
        for j in self._joints:  # every joint of this component that the model knows
            names = dyn.model.joint_names
            if j.name in names:
                k = names.index(j.name)
                q[k] = s[j.sp] if j.sp >= 0 else 0.0
                v[k] = s[j.sv] if j.sv >= 0 and math.isfinite(s[j.sv]) else 0.0
        idx = [k for _, k in self._effort_joints]
        tau = np.array([c[j.ce] if math.isfinite(c[j.ce]) else 0.0 for j, _ in self._effort_joints])
        damping = np.array([self._damping.get(j.name, 0.0) for j, _ in self._effort_joints])
        steps = max(1, math.ceil(dt / self.effort_substep_s - 1e-9))
        h = dt / steps
        acc = np.zeros(len(idx))
        M = dyn.mass_matrix(q)[np.ix_(idx, idx)]  # once per period: it changes slowly
        for _ in range(steps):
            rhs = tau - dyn.nonlinear_effects(q, v)[idx] - damping * v[idx]
            acc = np.asarray(np.linalg.solve(M, rhs), dtype=np.float64)
            v[idx] += acc * h
            q[idx] += v[idx] * h
        for (j, k), a in zip(self._effort_joints, acc, strict=True):
            if j.sp >= 0:
                s[j.sp] = float(q[k])
            if j.sv >= 0:
                s[j.sv] = float(v[k])
            if j.sa >= 0:
                s[j.sa] = float(a)
            if j.se >= 0:
                s[j.se] = c[j.ce] if math.isfinite(c[j.ce]) else 0.0

    def write(self, time_s: float, period_s: float) -> ReturnType:
        return ReturnType.OK  # the "simulation" happens in read(), as upstream
