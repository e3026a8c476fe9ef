"""robot_state_publisher's transforms, computed from a model and joint values (static mode).

Matches ``robot_state_publisher`` (``setupURDF``/``publishTransforms``): fixed joints go to
``/tf_static``; so do planar joints, as identity motion at their origin (kdl_parser turns them
into fixed joints); floating joints are skipped (someone else publishes them); revolute,
continuous and prismatic joints go to ``/tf`` with mimic joints following their source.
``frame_prefix`` is prepended verbatim (no ``/`` added) to both frame ids.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numpy.typing import ArrayLike

from robomodel.description import JointType
from robomodel.kinematics import Kinematics
from robomodel.tf.buffer import BufferCore
from robomodel.tf.message import TransformStamped

__all__ = ["DEFAULT_AUTHORITY", "buffer_from_model", "joint_state_defaults", "robot_transforms"]

DEFAULT_AUTHORITY = "default_authority"  # what rclpy's Buffer records (view_frames shows it)


def joint_state_defaults(kin: Kinematics) -> Mapping[str, float]:
    """joint_state_publisher's starting values: 0, or the middle of the limits if 0 is outside.

    Continuous joints count as [-pi, pi] (so 0); floating and planar joints are not published
    by joint_state_publisher and stay at their neutral value.
    """
    values: dict[str, float] = {}
    for name in kin.joint_names:
        joint = kin.robot.joint(name)
        if joint.type not in (JointType.REVOLUTE, JointType.PRISMATIC):
            continue
        lower, upper = (
            float(kin.lower[kin.q_slice(name)][0]),
            float(kin.upper[kin.q_slice(name)][0]),
        )
        values[name] = (lower + upper) / 2.0 if lower > 0.0 or upper < 0.0 else 0.0
    return values


def robot_transforms(
    kin: Kinematics, q: ArrayLike, *, frame_prefix: str = "", stamp_ns: int = 0
) -> tuple[list[TransformStamped], list[TransformStamped]]:
    """``(dynamic, static)`` transforms robot_state_publisher would send for ``q``."""
    Ts = kin.fk(q)
    index = {name: i for i, name in enumerate(kin.link_names)}
    dynamic: list[TransformStamped] = []
    static: list[TransformStamped] = []
    tree = kin.robot.tree()
    for link in kin.link_names[1:]:
        joint = tree.parent_joint[link]
        parent, child = frame_prefix + joint.parent, frame_prefix + joint.child
        if joint.type is JointType.FLOATING:
            continue
        if joint.type in (JointType.FIXED, JointType.PLANAR):
            static.append(
                TransformStamped.from_matrix(parent, child, joint.origin.matrix(), stamp_ns)
            )
            continue
        T = np.linalg.solve(Ts[index[joint.parent]], Ts[index[joint.child]])
        dynamic.append(TransformStamped.from_matrix(parent, child, T, stamp_ns))
    return dynamic, static


def buffer_from_model(
    kin: Kinematics,
    q: ArrayLike,
    *,
    frame_prefix: str = "",
    stamp_ns: int = 0,
    buffer: BufferCore | None = None,
) -> BufferCore:
    """A buffer holding what robot_state_publisher would publish for ``q``."""
    buf = BufferCore() if buffer is None else buffer
    dynamic, static = robot_transforms(kin, q, frame_prefix=frame_prefix, stamp_ns=stamp_ns)
    for msg in static:
        buf.set_transform(msg, DEFAULT_AUTHORITY, is_static=True)
    for msg in dynamic:
        buf.set_transform(msg, DEFAULT_AUTHORITY, is_static=False)
    return buf
