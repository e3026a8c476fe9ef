"""Divergence checks of the physics state: NaN/infinite values or MuJoCo's "bad qacc" reset.

Run every 100 physics steps and after each :meth:`~robomodel.sim.Simulation.step` call, so the
common case (a finite state, no warning) is a handful of scalar reads; the exact search for the
first bad joint and body only runs once something is wrong.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np

from robomodel.sim._mujoco import mujoco
from robomodel.sim.exceptions import DivergenceError

__all__ = ["check_finite"]


@functools.cache
def _bad_warnings() -> list[int]:
    """mjWARN_BADQACC, mjWARN_BADQVEL, mjWARN_BADQPOS, in the order they are reported."""
    w = mujoco().mjtWarning
    return [int(w.mjWARN_BADQACC), int(w.mjWARN_BADQVEL), int(w.mjWARN_BADQPOS)]


def check_finite(model: Any, data: Any) -> None:
    """Raise :class:`DivergenceError` naming the joint and body if the state is not finite.

    Args:
        model: The compiled ``mujoco.MjModel``.
        data: Its ``mujoco.MjData``.
    """
    counts = data.warning.number  # one array of counts: cheap to test when all is well
    bad_warnings = _bad_warnings()
    if counts[bad_warnings].any():
        mj = mujoco()
        bad = next(mj.mjtWarning(w) for w in bad_warnings if counts[w] > 0)
        dof = int(data.warning[int(bad)].lastinfo)
        _diverged(model, data, f"MuJoCo reported {bad.name} (it would reset the state)", dof)
    qpos, qvel = data.qpos, data.qvel
    # Sums of finite values are finite unless they overflow; then the exact test below decides.
    if math.isfinite(float(qpos.sum()) + float(qvel.sum())):
        return
    if np.isfinite(qpos).all() and np.isfinite(qvel).all():
        return
    bad_q = np.flatnonzero(~np.isfinite(qvel))
    dof = int(bad_q[0]) if len(bad_q) else -1
    if dof < 0:
        qbad = int(np.flatnonzero(~np.isfinite(qpos))[0])
        jid = int(np.searchsorted(model.jnt_qposadr, qbad, side="right") - 1)
        dof = int(model.jnt_dofadr[jid])
    _diverged(model, data, "the state became NaN/infinite", dof)


def _diverged(model: Any, data: Any, what: str, dof: int) -> None:
    mj = mujoco()
    joint = body = "?"
    if 0 <= dof < model.nv:
        jid = int(model.dof_jntid[dof])
        joint = mj.mj_id2name(model, mj.mjtObj.mjOBJ_JOINT, jid) or f"joint {jid}"
        bid = int(model.jnt_bodyid[jid])
        body = mj.mj_id2name(model, mj.mjtObj.mjOBJ_BODY, bid) or f"body {bid}"
    raise DivergenceError(
        f"simulation diverged at t = {float(data.time):.4f} s: {what}; body '{body}' "
        f"(joint '{joint}') diverged first. Check its inertia, joint damping, controller "
        "gains and commands, or use a smaller physics step",
        name=body,
    )
