"""A robot session's joint panel and what its controls do (the sliders, Randomize, Center and
the floating and planar joints' poses), run on the executor thread unless said otherwise."""

from __future__ import annotations

import random
import threading
from abc import abstractmethod
from collections.abc import Mapping
from typing import Any

from robomodel.description.model import JointType, Robot
from robomodel.runtime.msg import TFMessage
from robomodel.runtime.node import Node
from robomodel.runtime.nodes.joint_state_publisher import JointStatePublisher
from robomodel.runtime.tf_listener import to_msg
from robomodel.tf import TransformStamped
from robomodel.viewer.bodies import body_transform
from robomodel.viewer.joint_panel import BodyPose, JointPanel
from robomodel.viewer.markup import md

__all__ = ["JointControls"]


class JointControls:
    """The joint panel part of :class:`~robomodel.viewer.session.RobotSession`, which sets
    these attributes."""

    robot: Robot | None
    jsp: JointStatePublisher | None
    panel: JointPanel | None
    bodies: dict[str, BodyPose]
    prefix: str
    external: bool
    _node: Node | None
    _tf_pub: Any
    _has_bodies: bool
    _pending: dict[str, float]
    _pending_lock: threading.Lock

    @property
    @abstractmethod
    def label(self) -> str:
        """The robot's name in the panel (RobotSession's)."""

    def build_panel(self, gui: Any, post: Any) -> None:
        """(Re)create the joint panel; ``post`` runs a callable on the executor thread."""
        if self.panel is not None:
            self.panel.remove()
            self.panel = None
        if self.robot is None:
            return
        if self.jsp is None:
            self.panel = JointPanel(
                gui,
                self.label,
                (),
                mimic={},
                bodies=(),
                on_change=lambda _p: None,
                on_randomize=lambda: None,
                on_center=lambda: None,
                on_body=lambda _n, _p: None,
                note=md("joint states come from the bus (`--joint-states external`)"),
            )
            return
        jsp = self.jsp
        bodies = tuple(
            j for j in self.robot.joints if j.type in (JointType.FLOATING, JointType.PLANAR)
        )
        mimic = {n: d.parent for n, d in jsp.dependent_joints.items()}
        self.panel = JointPanel(
            gui,
            self.label,
            tuple(jsp.free_joints.values()),
            mimic=mimic,
            bodies=bodies,
            on_change=self.queue_positions,
            on_randomize=lambda: post(lambda: self.randomize()),
            on_center=lambda: post(lambda: self.center()),
            on_body=lambda name, pose: post(lambda: self.set_body(name, pose)),
            units={j.name: "m" for j in self.robot.joints if j.type is JointType.PRISMATIC},
        )

    # -- controls (run on the executor thread) --------------------------------------------------
    def queue_positions(self, values: Mapping[str, float]) -> None:
        """From any thread: joint values to apply at the loop's next turn (merged, so a fast
        slider drag costs one joint_state_publisher message per turn, not one per event)."""
        with self._pending_lock:
            self._pending.update(values)

    def apply_queued(self) -> bool:
        """Apply queued joint values (loop thread); True if there were any."""
        with self._pending_lock:
            pending, self._pending = self._pending, {}
        if pending:
            self.set_positions(pending)
        return bool(pending)

    def set_positions(self, values: Mapping[str, float]) -> None:
        if self.jsp is None:
            return
        known = {k: v for k, v in values.items() if k in self.jsp.free_joints}
        self.jsp.set_positions(known)
        self.jsp.publish_now()

    def randomize(self, rng: random.Random | None = None) -> None:
        if self.jsp is None:
            return
        self.jsp.randomize(rng)
        self.jsp.publish_now()
        self._sync_sliders()

    def center(self) -> None:
        if self.jsp is None:
            return
        self.jsp.center()
        self.jsp.publish_now()
        self._sync_sliders()

    def _sync_sliders(self) -> None:
        if self.panel is not None and self.jsp is not None:
            self.panel.set_values(
                {n: j.position for n, j in self.jsp.free_joints.items() if j.position is not None}
            )

    def _body_joint(self, name: str) -> Any:
        if self.robot is None or not self.robot.has_joint(name):
            return None
        joint = self.robot.joint(name)
        return joint if joint.type in (JointType.FLOATING, JointType.PLANAR) else None

    def set_body(self, name: str, pose: BodyPose) -> None:
        self.bodies[name] = pose
        self.publish_bodies()

    def publish_bodies(self) -> None:
        """Publish floating and planar joints on /tf (robot_state_publisher does not)."""
        if self.robot is None or self._node is None or self.external or not self._has_bodies:
            return
        stamp = self._node.now()
        transforms = []
        for joint in self.robot.joints:
            if joint.type not in (JointType.FLOATING, JointType.PLANAR):
                continue
            T = body_transform(joint, self.bodies.get(joint.name, BodyPose()))
            transforms.append(
                to_msg(
                    TransformStamped.from_matrix(
                        self.prefix + joint.parent,
                        self.prefix + joint.child,
                        T,
                        stamp.to_nanoseconds(),
                    )
                )
            )
        if transforms:
            self._tf_pub.publish(TFMessage(transforms))
