"""joint_state_broadcaster: publishes the joints' state interfaces as sensor_msgs/JointState.

ros2_controllers joint_state_broadcaster.cpp: claims all state interfaces unless ``joints``
and ``interfaces`` are both given; one entry per joint having a position, velocity or effort
state (renamed through ``map_interface_to_joint_state.*``), NaN where an interface is missing,
``extra_joints`` appended with zeros; ``joint_states`` in the manager's namespace
(``~/joint_states`` with ``use_local_topics``), ``header.frame_id`` = ``frame_id`` (default ``base_link``), published
every update. ``publish_rate`` [Hz] (ROS 1's JointStateController, required there) limits
publishing as joint_state_controller.cpp does: publish when ``last_publish_time + 1/rate <
time``, then advance ``last_publish_time`` by ``1/rate``, so the mean rate is the one asked
for, not the loop's rate or a divisor of it.
"""

from __future__ import annotations

import math

from robomodel.control.controllers.base import (
    ControllerInterface,
    InterfaceConfiguration,
    ReturnType,
)
from robomodel.runtime.msg import DynamicJointState, Header, InterfaceValue, JointState, Time
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
        # relative, as ros2_controllers' (topic_name_prefix + "joint_states") and ROS 1's
        # JointStateController (root_nh "joint_states"): /<manager namespace>/joint_states
        self.topic = str(self.param("topic", "joint_states"))
        self.mapping = {
            str(self.param(f"map_interface_to_joint_state.{k}", k)): k
            for k in ("position", "velocity", "effort")
        }
        self.publish_dynamic_joint_states = bool(
            self.param("publish_dynamic_joint_states", True)  # humble default (master: false)
        )
        self.publish_rate_hz = float(self.param("publish_rate", 0.0))
        self._last_publish_s: float | None = None
        self._pub: Publisher[JointState] | None = None
        self._dyn_pub: Publisher[DynamicJointState] | None = None
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
            topic = "~/joint_states" if self.use_local_topics else self.topic
            self._pub = self.node.create_publisher(JointState, topic, 10)
            if self.publish_dynamic_joint_states:
                dyn = "~/dynamic_joint_states" if self.use_local_topics else "dynamic_joint_states"
                self._dyn_pub = self.node.create_publisher(DynamicJointState, dyn, 10)

    def on_cleanup(self) -> None:
        for pub in (self._pub, self._dyn_pub):
            if pub is not None:
                pub.destroy()
        self._pub = None
        self._dyn_pub = None

    def on_activate(self) -> None:
        self._last_publish_s = None  # starting(time): set at the first update
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
        self._values = self.state_interfaces[0].table if self.state_interfaces else []
        # /dynamic_joint_states: every state interface, grouped by prefix in claim order
        groups: dict[str, list[tuple[str, int]]] = {}
        for si in self.state_interfaces:
            groups.setdefault(si.prefix, []).append((si.interface, si.slot))
        self._dyn_names = list(groups)
        self._dyn_groups = [
            ([name for name, _ in items], [slot for _, slot in items]) for items in groups.values()
        ]

    def _due(self, time_s: float) -> bool:
        """ROS 1's rate limit (see the module docstring); always due without ``publish_rate``."""
        if self.publish_rate_hz <= 0.0:
            return True
        if self._last_publish_s is None:
            self._last_publish_s = time_s
            return False
        interval_s = 1.0 / self.publish_rate_hz
        if self._last_publish_s + interval_s < time_s:
            self._last_publish_s += interval_s
            return True
        return False

    def update(self, time_s: float, period_s: float) -> ReturnType:
        if not self._due(time_s):
            return ReturnType.OK
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
        if self._dyn_pub is not None:
            sec = math.floor(time_s)
            self._dyn_pub.publish(
                DynamicJointState(
                    Header(Time(int(sec), int((time_s - sec) * 1e9)), self.frame_id),
                    self._dyn_names,
                    [
                        InterfaceValue(names, [values[s] for s in slots])
                        for names, slots in self._dyn_groups
                    ],
                )
            )
        return ReturnType.OK
