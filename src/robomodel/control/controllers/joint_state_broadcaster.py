"""joint_state_broadcaster: publishes the joints' state interfaces as sensor_msgs/JointState.

ros2_controllers joint_state_broadcaster.cpp: claims all state interfaces unless ``joints``
and ``interfaces`` are both given; one entry per joint having a position, velocity or effort
state (renamed through ``map_interface_to_joint_state.*``), NaN where an interface is missing,
``extra_joints`` appended with zeros; ``/joint_states`` (``~/joint_states`` with
``use_local_topics``), ``header.frame_id`` = ``frame_id`` (default ``base_link``), published
every update (ROS 1's JointStateController ``publish_rate`` maps onto the update rate).
"""

from __future__ import annotations

import math

from robomodel.control.controllers.base import (
    ControllerInterface,
    InterfaceConfiguration,
    ReturnType,
)
from robomodel.runtime.msg import Header, JointState, Time
from robomodel.runtime.node import Publisher

__all__ = ["JointStateBroadcaster"]


class JointStateBroadcaster(ControllerInterface):
    """``joint_state_broadcaster/JointStateBroadcaster`` (see the module docstring)."""

    type_name = "joint_state_broadcaster/JointStateBroadcaster"

    def on_init(self) -> None:
        self.joints = self.param_list("joints", [])
        self.interfaces = self.param_list("interfaces", [])
        self.extra_joints = self.param_list("extra_joints", [])
        self.frame_id = str(self.param("frame_id", "base_link"))
        self.use_local_topics = bool(self.param("use_local_topics", False))
        self.mapping = {
            str(self.param(f"map_interface_to_joint_state.{k}", k)): k
            for k in ("position", "velocity", "effort")
        }
        self._pub: Publisher[JointState] | None = None
        self.msg = JointState()
        self._copies: list[tuple[int, list[float], int]] = []

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def state_interface_configuration(self) -> InterfaceConfiguration:
        if self.joints and self.interfaces:
            return InterfaceConfiguration.individual(
                [f"{j}/{i}" for j in self.joints for i in self.interfaces]
            )
        return InterfaceConfiguration.all()

    def on_configure(self) -> None:
        if self.node is not None:
            topic = "~/joint_states" if self.use_local_topics else "/joint_states"
            self._pub = self.node.create_publisher(JointState, topic, 10)

    def on_cleanup(self) -> None:
        if self._pub is not None:
            self._pub.destroy()
            self._pub = None

    def on_activate(self) -> None:
        names: list[str] = []
        for si in self.state_interfaces:
            if si.interface in self.mapping and si.prefix not in names:
                names.append(si.prefix)
        n = len(names)
        self.msg = JointState(
            header=Header(frame_id=self.frame_id),
            name=names + self.extra_joints,
            position=[math.nan] * n + [0.0] * len(self.extra_joints),
            velocity=[math.nan] * n + [0.0] * len(self.extra_joints),
            effort=[math.nan] * n + [0.0] * len(self.extra_joints),
        )
        arrays = {
            "position": self.msg.position,
            "velocity": self.msg.velocity,
            "effort": self.msg.effort,
        }
        self._copies = [
            (si.slot, arrays[self.mapping[si.interface]], names.index(si.prefix))
            for si in self.state_interfaces
            if si.interface in self.mapping
        ]
        self._values = self.state_interfaces[0]._values if self.state_interfaces else []

    def update(self, time_s: float, period_s: float) -> ReturnType:
        values = self._values
        for slot, array, k in self._copies:
            array[k] = values[slot]
        if self._pub is not None:  # a fresh message: in-process subscribers keep the object
            sec = math.floor(time_s)
            m = self.msg
            self._pub.publish(
                JointState(
                    Header(Time(int(sec), int((time_s - sec) * 1e9)), self.frame_id),
                    m.name,
                    m.position[:],
                    m.velocity[:],
                    m.effort[:],
                )
            )
        return ReturnType.OK
