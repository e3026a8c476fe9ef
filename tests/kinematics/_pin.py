"""Mapping robomodel configurations to pinocchio's ``q`` (used by the tests only).

pinocchio differs in three documented ways, converted here rather than in the product:
continuous joints take ``(cos, sin)``; planar joints take ``(x, y, cos, sin)`` with the plane
always normal to z (the URDF axis is ignored); mimic joints are independent joints unless
``mimic=True`` is passed to ``buildModelFromUrdf``, so we set them to ``multiplier * source +
offset`` ourselves.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio

from robomodel.kinematics import Kinematics


def pin_q(kin: Kinematics, model: pinocchio.Model, q: np.ndarray) -> np.ndarray:
    values: dict[str, np.ndarray] = {}
    for name in kin.joint_names:
        values[name] = np.asarray(q[kin.q_slice(name)])
    for name, (source, factor, offset) in kin.mimic.items():
        values[name] = factor * np.asarray(q[kin.q_slice(source)]) + offset
    out = pinocchio.neutral(model)
    for jid in range(1, model.njoints):
        name = model.names[jid]
        joint = model.joints[jid]
        v = values[name]
        start, nq = joint.idx_q, joint.nq
        short = joint.shortname()
        if short == "JointModelFreeFlyer":
            out[start : start + 7] = v
        elif short == "JointModelPlanar":
            out[start : start + 4] = [v[0], v[1], math.cos(v[2]), math.sin(v[2])]
        elif nq == 2:  # continuous (revolute unbounded)
            out[start : start + 2] = [math.cos(v[0]), math.sin(v[0])]
        else:
            out[start] = v[0]
    return out


def pin_link_poses(kin: Kinematics, model: pinocchio.Model, q: np.ndarray) -> np.ndarray:
    data = model.createData()
    pinocchio.framesForwardKinematics(model, data, pin_q(kin, model, q))
    poses = []
    for name in kin.link_names:
        fid = model.getFrameId(name, pinocchio.BODY)
        poses.append(data.oMf[fid].homogeneous)
    return np.array(poses)
