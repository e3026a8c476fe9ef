"""Small helpers shared by the sensor and navigation displays (placement and status text)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer._poses import wxyz_xyz_from_matrix
from robomodel.viewer.displays.base import DisplayStatus, FrameLookup, Placement, stamp_ns

__all__ = ["combine", "place", "pose_kwargs"]


def place(lookup: FrameLookup, header: Any) -> Placement:
    """Where a message's ``header.frame_id`` is in the fixed frame at its ``header.stamp``."""
    return lookup(str(header.frame_id), stamp_ns(header.stamp))


def pose_kwargs(T: NDArray[np.float64]) -> dict[str, Any]:
    """viser's ``wxyz`` and ``position`` keyword arguments of a 4x4 pose."""
    wxyz, xyz = wxyz_xyz_from_matrix(T)
    return {"wxyz": wxyz, "position": xyz}


def combine(base: DisplayStatus | None, problems: list[str], ok_text: str) -> DisplayStatus:
    """The display's status: the first problem (an error, with how many more), else the
    topic's warning ("No messages received"), else ``ok_text``."""
    if problems:
        more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
        return DisplayStatus.error(problems[0] + more)
    if base is not None:
        return base
    return DisplayStatus.ok(ok_text)
