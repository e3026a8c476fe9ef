"""Contact (bumper) sensor: the contacts of the sensor's link (gazebo_ros_bumper)."""

from __future__ import annotations

import numpy as np

from robomodel.runtime.msg.schema import Message
from robomodel.runtime.msg.types.geometry_msgs import Vector3
from robomodel.sim._mujoco import mujoco
from robomodel.sim.sensors.base import SimSensor
from robomodel.sim.sensors.msgs import ContactsState, ContactState

__all__ = ["ContactSensor"]


class ContactSensor(SimSensor):
    message_type = ContactsState

    def measure(self, time_s: float) -> Message:
        mj = mujoco()
        m, d = self.model, self.data
        states: list[ContactState] = []
        force = np.zeros(6)
        for i in range(d.ncon):
            contact = d.contact[i]
            g1, g2 = int(contact.geom1), int(contact.geom2)
            if self.body not in (int(m.geom_bodyid[g1]), int(m.geom_bodyid[g2])):
                continue
            mj.mj_contactForce(m, d, i, force)
            world = contact.frame.reshape(3, 3).T @ force[:3]
            states.append(
                ContactState(
                    info=f"contact {i}",
                    collision1_name=m.geom(g1).name,
                    collision2_name=m.geom(g2).name,
                    total_wrench_force=Vector3(*(float(v) for v in world)),
                    depths=[float(-contact.dist)],
                )
            )
        return ContactsState(header=self.header(time_s), states=states)
