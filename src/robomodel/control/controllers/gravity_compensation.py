"""A gravity-compensation effort controller (robomodel; no ros2_controllers equivalent).

Writes ``g(q)`` (:meth:`robomodel.kinematics.Dynamics.gravity`) plus an optional joint PD
(``kp``, ``kd`` towards the position held at activation) to the effort of ``joints``.
"""

from __future__ import annotations

import numpy as np

from robomodel.control.controllers.base import (
    ControllerInterface,
    InterfaceConfiguration,
    ReturnType,
)
from robomodel.control.controllers.exceptions import ControllerError

__all__ = ["GravityCompensationController"]


class GravityCompensationController(ControllerInterface):
    """``robomodel_controllers/GravityCompensationController`` (``joints``, ``kp``, ``kd``)."""

    type_name = "robomodel_controllers/GravityCompensationController"

    def on_init(self) -> None:
        if self.robot is None:
            raise ControllerError(f"controller '{self.name}' needs the robot description")
        from robomodel.kinematics import Kinematics

        kin = Kinematics(self.robot)
        self.dynamics = kin.dynamics()
        self.joints = self.param_list("joints", list(kin.joint_names))
        missing = [j for j in self.joints if j not in kin.joint_names]
        if missing:
            raise ControllerError(
                f"controller '{self.name}': joints {missing} are not actuated joints of the model"
            )
        self.kp = self.param_float("kp", 0.0)
        self.kd = self.param_float("kd", 0.0)
        self._index = [kin.joint_names.index(j) for j in self.joints]
        self._all = list(kin.joint_names)

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual([f"{j}/effort" for j in self.joints])

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.all()

    def on_activate(self) -> None:
        by_name = {si.name: si for si in self.state_interfaces}
        self._pos = [by_name.get(f"{j}/position") for j in self._all]
        self._vel = [by_name.get(f"{j}/velocity") for j in self._all]
        self.hold = self._q()

    def _q(self) -> np.ndarray:
        return np.array([0.0 if si is None else si.get() for si in self._pos])

    def update(self, time_s: float, period_s: float) -> ReturnType:
        q = self._q()
        v = np.array([0.0 if si is None else si.get() for si in self._vel])
        tau = self.dynamics.gravity(q) + self.kp * (self.hold - q) - self.kd * v
        for ci, k in zip(self.command_interfaces, self._index, strict=True):
            ci.set(float(tau[k]))
        return ReturnType.OK
