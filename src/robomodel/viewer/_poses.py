"""Small vectorised pose helpers (rotation matrices to ``wxyz`` quaternions)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["wxyz_from_matrices", "wxyz_xyz_from_matrix"]


def wxyz_from_matrices(R: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit quaternions ``wxyz`` (shape (N, 4), w >= 0) of rotation matrices (N, 3, 3).

    Shepperd's method: pick the largest of w, x, y, z to divide by, for every row.
    """
    R = np.asarray(R, dtype=np.float64).reshape(-1, 3, 3)
    m00, m11, m22 = R[:, 0, 0], R[:, 1, 1], R[:, 2, 2]
    candidates = np.stack(
        [1 + m00 + m11 + m22, 1 + m00 - m11 - m22, 1 - m00 + m11 - m22, 1 - m00 - m11 + m22],
        axis=1,
    )
    pick = np.argmax(candidates, axis=1)
    q = np.empty((R.shape[0], 4))
    s = np.sqrt(np.maximum(candidates[np.arange(R.shape[0]), pick], 1e-300)) * 2.0
    d21, d02, d10 = R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]
    s21, s02, s10 = R[:, 2, 1] + R[:, 1, 2], R[:, 0, 2] + R[:, 2, 0], R[:, 1, 0] + R[:, 0, 1]
    rows = [
        np.stack([s / 4, d21 / s, d02 / s, d10 / s], axis=1),
        np.stack([d21 / s, s / 4, s10 / s, s02 / s], axis=1),
        np.stack([d02 / s, s10 / s, s / 4, s21 / s], axis=1),
        np.stack([d10 / s, s02 / s, s21 / s, s / 4], axis=1),
    ]
    for k in range(4):
        mask = pick == k
        q[mask] = rows[k][mask]
    q *= np.where(q[:, :1] < 0, -1.0, 1.0)
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    return q


def wxyz_xyz_from_matrix(
    T: NDArray[np.float64],
) -> tuple[tuple[float, float, float, float], tuple[float, float, float]]:
    """``(wxyz, xyz)`` of one 4x4 transform, as plain tuples for viser's ``wxyz``/``position``."""
    w, x, y, z = (float(v) for v in wxyz_from_matrices(T[:3, :3])[0])
    return (w, x, y, z), (float(T[0, 3]), float(T[1, 3]), float(T[2, 3]))
