"""robot_state_publisher with ROS 2's semantics (ros/robot_state_publisher 3.3).

Parameters: ``robot_description`` (URDF text; also published latched on ``robot_description``),
``publish_frequency`` (a rate limiter in [0, 1000] Hz, 20 by default; 0 disables limiting),
``ignore_timestamp`` and ``frame_prefix`` (prepended verbatim to every frame id). Fixed and
planar joints go to /tf_static once, and again when the description changes; floating joints
are skipped (kdl_parser turns planar and floating into fixed joints, and RSP drops floating
ones). Movable joints go to /tf for each /joint_states message, stamped with its header.
Unknown joint names are ignored; mimic joints are inserted from their source only if the
message does not carry them (one level, as upstream).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from robomodel.description import read_urdf
from robomodel.description.model import Joint, JointType, Robot
from robomodel.description.rigid import QuatXyzw, Vec3, qmul_xyzw
from robomodel.description.urdf.writer import urdf_to_string
from robomodel.errors import RobomodelError
from robomodel.runtime.context import Context
from robomodel.runtime.msg import (
    Header,
    JointState,
    Quaternion,
    String,
    TFMessage,
    Time,
    Transform,
    TransformStamped,
    Vector3,
)
from robomodel.runtime.node import Node
from robomodel.runtime.params import SetResult
from robomodel.runtime.qos import latched, sensor_data

__all__ = ["RobotStatePublisher"]

_MOVABLE = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC)
_STATIC = (JointType.FIXED, JointType.PLANAR)


@dataclass(frozen=True, slots=True)
class _Segment:
    """One joint, precomputed so that a pose costs a few float operations (KDL's Segment)."""

    joint: Joint
    xyz: Vec3
    rotation: QuatXyzw  # of the origin
    axis_in_parent: Vec3  # origin rotation applied to the unit axis (for prismatic travel)
    rotation_times_axis: (
        QuatXyzw  # rotation ⊗ (unit axis, 0): a revolute pose is linear in sin, cos
    )
    revolute: bool  # revolute or continuous
    prismatic: bool

    @classmethod
    def of(cls, joint: Joint) -> _Segment:
        axis = np.asarray(joint.axis, dtype=np.float64)
        norm = float(np.linalg.norm(axis))
        if joint.type in _MOVABLE and norm == 0.0:
            raise RobomodelError(
                f"joint '{joint.name}' has a zero axis; robot_state_publisher needs a direction"
            )
        unit = axis / norm if norm else axis  # KDL normalises the axis
        R = joint.origin.matrix()[:3, :3]
        ux, uy, uz = (float(v) for v in unit)
        px, py, pz = (float(v) for v in R @ unit)
        rotation = joint.origin.quaternion_xyzw()
        return cls(
            joint,
            joint.origin.xyz_m,
            rotation,
            (px, py, pz),
            qmul_xyzw(rotation, (ux, uy, uz, 0.0)),
            joint.type in (JointType.REVOLUTE, JointType.CONTINUOUS),
            joint.type is JointType.PRISMATIC,
        )

    def message(self, value: float, prefix: str, stamp: Time) -> TransformStamped:
        """The child's pose in the parent at ``value`` [rad or m] (once per joint per
        /joint_states, so the pose is computed inline)."""
        x, y, z = self.xyz
        qx, qy, qz, qw = self.rotation
        if self.revolute:
            # rotation ⊗ (axis sin(v/2), cos(v/2)) = sin(v/2) rotation⊗(axis, 0) + cos(v/2) rotation
            half = 0.5 * value
            s, c = math.sin(half), math.cos(half)
            ax, ay, az, aw = self.rotation_times_axis
            qx, qy, qz, qw = ax * s + qx * c, ay * s + qy * c, az * s + qz * c, aw * s + qw * c
        elif self.prismatic:
            px, py, pz = self.axis_in_parent
            x, y, z = x + px * value, y + py * value, z + pz * value
        joint = self.joint
        return TransformStamped(
            Header(stamp, prefix + joint.parent),
            prefix + joint.child,
            Transform(Vector3(x, y, z), Quaternion(qx, qy, qz, qw)),
        )


@dataclass(frozen=True, slots=True)
class _Segments:
    robot: Robot
    movable: dict[str, _Segment]
    fixed: tuple[_Segment, ...]
    mimic: tuple[tuple[str, str, float, float], ...]  # (joint, source, multiplier, offset)


def _segments(robot: Robot) -> _Segments:
    movable = {j.name: _Segment.of(j) for j in robot.joints if j.type in _MOVABLE}
    fixed = tuple(_Segment.of(j) for j in robot.joints if j.type in _STATIC)
    mimic = tuple(
        (j.name, j.mimic.joint, j.mimic.multiplier_or_default, j.mimic.offset_or_default)
        for j in sorted(robot.joints, key=lambda j: j.name)
        if j.mimic is not None
    )
    return _Segments(robot, movable, fixed, mimic)


class RobotStatePublisher:
    """The robot_state_publisher node (see the module docstring for the semantics).

    Args:
        context: Where the node lives.
        robot_description: URDF text or a parsed :class:`Robot`; overrides the parameter.
        parameters: Node parameter overrides (``publish_frequency``, ``frame_prefix``, ...).
    """

    def __init__(
        self,
        context: Context,
        robot_description: str | Robot | None = None,
        *,
        name: str = "robot_state_publisher",
        namespace: str = "/",
        parameters: Mapping[str, Any] | None = None,
        remappings: Mapping[str, str] | None = None,
    ) -> None:
        overrides = dict(parameters or {})
        if isinstance(robot_description, Robot):
            overrides["robot_description"] = urdf_to_string(robot_description)
        elif robot_description is not None:
            overrides["robot_description"] = robot_description
        self.node: Node = context.create_node(
            name, namespace, parameters=overrides, remappings=remappings
        )
        node = self.node
        description = str(node.declare_parameter("robot_description", ""))
        if not description:
            raise RobomodelError("robot_description parameter must not be empty")
        frequency = float(node.declare_parameter("publish_frequency", 20.0))
        if not 0.0 <= frequency <= 1000.0:
            raise RobomodelError("publish_frequency must be between 0 and 1000")
        node.declare_parameter("ignore_timestamp", False)
        node.declare_parameter("frame_prefix", "")
        self.description_pub = node.create_publisher(String, "robot_description", latched())
        self.tf_pub = node.create_publisher(TFMessage, "/tf", 100)
        self.tf_static_pub = node.create_publisher(TFMessage, "/tf_static", latched())
        self._last_publish_ns: dict[str, int] = {}
        self._last_callback_ns = 0
        self._segments = self._parse(description)
        if isinstance(robot_description, Robot):
            self._segments = _segments(robot_description)
        node.parameters.add_set_callback(self._validate)
        node.parameters.add_post_set_callback(self._apply)
        node.create_subscription(JointState, "joint_states", self.on_joint_state, sensor_data())
        self._setup(description)

    @property
    def robot(self) -> Robot:
        return self._segments.robot

    # -- description --------------------------------------------------------------------------
    @staticmethod
    def _parse(description: str) -> _Segments:
        return _segments(read_urdf(description, path="robot_description").robot)

    def _validate(self, changes: Mapping[str, Any]) -> SetResult:
        if "robot_description" in changes:
            text = str(changes["robot_description"])
            if not text:
                return SetResult(False, "Empty URDF is not allowed")
            try:
                self._parse(text)
            except RobomodelError as exc:
                return SetResult(False, str(exc))
        if (
            "publish_frequency" in changes
            and not 0.0 <= float(changes["publish_frequency"]) <= 1000.0
        ):
            return SetResult(False, "publish_frequency must be between 0.0 and 1000.0")
        return SetResult(True)

    def _apply(self, changes: Mapping[str, Any]) -> None:
        if "robot_description" in changes:
            text = str(changes["robot_description"])
            self._segments = self._parse(text)
            self._setup(text)

    def _setup(self, description: str) -> None:
        self.description_pub.publish(String(description))
        self.publish_fixed_transforms()

    # -- publishing ---------------------------------------------------------------------------
    def _prefix(self) -> str:
        return str(self.node.get_parameter("frame_prefix"))

    def publish_fixed_transforms(self) -> None:
        """All fixed (and planar) joints, stamped now, as one latched /tf_static message."""
        stamp, prefix = self.node.now(), self._prefix()
        transforms = [segment.message(0.0, prefix, stamp) for segment in self._segments.fixed]
        self.tf_static_pub.publish(TFMessage(transforms))

    def on_joint_state(self, msg: JointState) -> None:
        """robot_state_publisher's ``callbackJointState``."""
        log = self.node.logger
        if len(msg.name) != len(msg.position):
            if not msg.position:
                names = ", ".join(f'"{n}"' for n in msg.name)
                log.warning(
                    "Robot state publisher ignored a JointState message about joint(s) %s whose position member was empty.",
                    names,
                )
            else:
                log.error("Robot state publisher ignored an invalid JointState message")
            return
        now_ns = self.node.get_clock().now_ns()
        if self._last_callback_ns > now_ns:
            log.warning("Moved backwards in time, re-publishing joint transforms!")
            self._last_publish_ns.clear()
        self._last_callback_ns = now_ns
        stamp_ns = msg.header.stamp.to_nanoseconds()
        frequency = float(self.node.get_parameter("publish_frequency"))
        if not self.node.get_parameter("ignore_timestamp") and frequency > 0:
            interval_ns = int(1000.0 / frequency) * 1_000_000  # whole milliseconds, as upstream
            last = min((self._last_publish_ns.get(n, 0) for n in msg.name), default=0)
            if stamp_ns < last + interval_ns:
                return
        positions = dict(zip(msg.name, msg.position, strict=True))
        for joint, source, multiplier, offset in self._segments.mimic:
            if source in positions and joint not in positions:
                positions[joint] = positions[source] * multiplier + offset
        self.publish_transforms(positions, msg.header.stamp)
        for name in msg.name:
            self._last_publish_ns[name] = stamp_ns

    def publish_transforms(self, positions: Mapping[str, float], stamp: Time) -> None:
        prefix = self._prefix()
        movable = self._segments.movable
        transforms = []
        for name, value in positions.items():
            segment = movable.get(name)
            if segment is None or not math.isfinite(value):
                continue
            transforms.append(segment.message(value, prefix, stamp))
        if transforms:
            self.tf_pub.publish(TFMessage(transforms))
