"""Where a robot's links (and the frames of no robot) are in the fixed frame, from the TF buffer."""

from __future__ import annotations

from collections.abc import Sequence, Set
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from robomodel.description.model import Robot
from robomodel.description.rigid import IDENTITY_POSE, PoseXyzw, compose_poses
from robomodel.tf import BufferCore
from robomodel.tf.exceptions import TransformError

__all__ = ["LinkPoseSolver", "LinkPoses", "StaleFrames", "append_other_frames"]


@dataclass(frozen=True, slots=True)
class LinkPoses:
    """Every link of a robot in the fixed frame (``link_names`` order).

    ``connected``: the root has a transform to the fixed frame; else it was placed beside it,
    and ``root_in_tf`` says whether TF has the root frame at all.
    """

    wxyz: NDArray[np.float64]
    xyz: NDArray[np.float64]
    visible: NDArray[np.bool_]
    connected: bool
    missing: tuple[str, ...]
    root_in_tf: bool = True


def _qmul_xyzw(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    ax, ay, az, aw = a[..., 0], a[..., 1], a[..., 2], a[..., 3]
    bx, by, bz, bw = b[..., 0], b[..., 1], b[..., 2], b[..., 3]
    return np.stack(
        [
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz,
        ],
        axis=-1,
    )


def _rotate_xyzw(q: NDArray[np.float64], v: NDArray[np.float64]) -> NDArray[np.float64]:
    u, w = q[..., :3], q[..., 3:4]
    t = 2.0 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


class LinkPoseSolver:
    """Every link of one robot in the fixed frame, from TF (the plan is made once per model).

    Each joint is looked up one hop (parent to child, with the frame prefix) and composed down
    the tree from the root, then the root is placed in the fixed frame. When the root has no
    transform to the fixed frame (another robot's tree), the robot is placed at
    ``T_fixed_root_default`` so that unconnected robots still appear side by side.
    """

    def __init__(self, robot: Robot, prefix: str, link_names: tuple[str, ...]) -> None:
        tree = robot.tree()
        self.robot = robot
        self.prefix = prefix
        self.link_names = link_names
        self._root = tree.root
        self._root_frame = prefix + tree.root
        # (parent link, child link, parent frame, child frame), parents before children: the
        # tree walk is the same every update, and it cost about a third of one at 1,000 links.
        self._hops = tuple(
            (joint.parent, joint.child, prefix + joint.parent, prefix + joint.child)
            for _depth, joint in tree.walk()
        )

    def solve(
        self, buffer: BufferCore, fixed_frame: str, T_fixed_root_default: NDArray[np.float64]
    ) -> LinkPoses:
        """Every link in the fixed frame, in ``link_names`` order."""
        root = self._root_frame
        names = self.link_names
        # Plain lists and floats while walking (numpy element access costs more than the
        # maths), one array per field at the end.
        poses: dict[str, PoseXyzw] = {self._root: IDENTITY_POSE}
        missing = []
        lookup = buffer.lookup_transform
        # One hop per joint (parent -> child), composed down the tree: O(links), not
        # O(links x depth) as looking every link up from the root would be.
        for parent, child, parent_frame, frame in self._hops:
            parent_pose = poses.get(parent)
            try:
                if parent_pose is None:
                    raise TransformError("parent not connected")
                tf = lookup(parent_frame, frame)
                poses[child] = compose_poses(parent_pose, (tf.translation_m, tf.rotation_xyzw))
            except TransformError:
                try:  # another process may publish a different tree: ask the root directly
                    tf = lookup(root, frame)
                except TransformError:
                    missing.append(frame)
                    continue
                poses[child] = (tf.translation_m, tf.rotation_xyzw)
        return _in_fixed_frame(
            [poses.get(name) for name in names],
            root,
            buffer,
            fixed_frame,
            T_fixed_root_default,
            tuple(missing),
        )


def _in_fixed_frame(
    rows: list[PoseXyzw | None],
    root: str,
    buffer: BufferCore,
    fixed_frame: str,
    T_fixed_root_default: NDArray[np.float64],
    missing: tuple[str, ...],
) -> LinkPoses:
    """Link poses in the root frame (None: not connected) placed in the fixed frame."""
    identity_xyzw = (0.0, 0.0, 0.0, 1.0)
    visible = np.array([row is not None for row in rows], dtype=bool)
    t = np.array([row[0] if row is not None else (0.0, 0.0, 0.0) for row in rows]).reshape(-1, 3)
    q = np.array([row[1] if row is not None else identity_xyzw for row in rows]).reshape(-1, 4)
    connected = root_in_tf = True
    try:
        base = buffer.lookup_transform(fixed_frame, root)
        t0 = np.asarray(base.translation_m)
        q0 = np.asarray(base.rotation_xyzw)
    except TransformError:
        connected = fixed_frame == root
        root_in_tf = connected or root in buffer.frames
        t0 = T_fixed_root_default[:3, 3].copy()
        q0 = np.array([0.0, 0.0, 0.0, 1.0])
    xyz = t0 + _rotate_xyzw(np.broadcast_to(q0, q.shape), t)
    q_fixed = _qmul_xyzw(np.broadcast_to(q0, q.shape), q)
    wxyz = np.concatenate([q_fixed[:, 3:4], q_fixed[:, :3]], axis=1)
    wxyz *= np.where(wxyz[:, :1] < 0, -1.0, 1.0)
    return LinkPoses(wxyz, xyz, visible, connected, missing, root_in_tf)


class StaleFrames(Protocol):
    """What :func:`append_other_frames` reads of a robot session: the TF frames its robot no
    longer has (a reloaded description's old links)."""

    @property
    def stale_frames(self) -> Set[str]: ...


def append_other_frames(
    buffer: BufferCore,
    fixed_frame: str,
    sessions: Sequence[StaleFrames],
    frames: list[str],
    wxyzs: list[np.ndarray],
    xyzs: list[np.ndarray],
    shown: list[np.ndarray],
) -> None:
    """TF frames that belong to no robot (from other processes): looked up directly.

    Appended to ``frames`` and their poses to ``wxyzs``, ``xyzs``, ``shown``; frames already
    in ``frames`` and the sessions' stale frames are skipped.
    """
    known = set(frames)
    stale = set().union(*(s.stale_frames for s in sessions))
    for frame in buffer.frames:
        if frame in known or frame in stale:
            continue
        try:
            tf = buffer.lookup_transform(fixed_frame, frame)
        except TransformError:
            continue
        x, y, z, w = tf.rotation_xyzw
        frames.append(frame)
        wxyzs.append(np.array([[w, x, y, z]]))
        xyzs.append(np.array([tf.translation_m]))
        shown.append(np.array([True]))
