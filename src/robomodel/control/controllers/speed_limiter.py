"""The humble diff_drive_controller speed limiter (src/speed_limiter.cpp).

``limit(v, v0, v1, dt)`` applies jerk, then acceleration, then velocity limits, where ``v0``
is the previous command and ``v1`` the one before; jerk bounds use ``2 dt²`` (humble).
``min_*`` default to ``-max_*``.
"""

from __future__ import annotations

import math

__all__ = ["SpeedLimiter"]


def _clamp(x: float, lo: float, hi: float) -> float:
    return min(max(x, lo), hi)


class SpeedLimiter:
    """Velocity, acceleration and jerk limits on one axis (``linear.x`` or ``angular.z``)."""

    def __init__(
        self,
        *,
        has_velocity_limits: bool = False,
        has_acceleration_limits: bool = False,
        has_jerk_limits: bool = False,
        min_velocity: float = math.nan,
        max_velocity: float = math.nan,
        min_acceleration: float = math.nan,
        max_acceleration: float = math.nan,
        min_jerk: float = math.nan,
        max_jerk: float = math.nan,
    ) -> None:
        def lo(mn: float, mx: float) -> float:  # speed_limiter.cpp: NaN min -> -max
            return -abs(mx) if math.isnan(mn) else mn

        self.has_velocity_limits = has_velocity_limits
        self.has_acceleration_limits = has_acceleration_limits
        self.has_jerk_limits = has_jerk_limits
        self.min_velocity, self.max_velocity = lo(min_velocity, max_velocity), max_velocity
        self.min_acceleration = lo(min_acceleration, max_acceleration)
        self.max_acceleration = max_acceleration
        self.min_jerk, self.max_jerk = lo(min_jerk, max_jerk), max_jerk

    def limit(self, v: float, v0: float, v1: float, dt: float) -> float:
        """The limited ``v``."""
        tmp = v
        tmp = self.limit_jerk(tmp, v0, v1, dt)
        tmp = self.limit_acceleration(tmp, v0, dt)
        return self.limit_velocity(tmp)

    def limit_velocity(self, v: float) -> float:
        if self.has_velocity_limits:
            return _clamp(v, self.min_velocity, self.max_velocity)
        return v

    def limit_acceleration(self, v: float, v0: float, dt: float) -> float:
        if self.has_acceleration_limits:
            dv = _clamp(v - v0, self.min_acceleration * dt, self.max_acceleration * dt)
            return v0 + dv
        return v

    def limit_jerk(self, v: float, v0: float, v1: float, dt: float) -> float:
        if self.has_jerk_limits:
            dv = v - v0
            dv0 = v0 - v1
            dt2 = 2.0 * dt * dt
            da = _clamp(dv - dv0, self.min_jerk * dt2, self.max_jerk * dt2)
            return v0 + dv0 + da
        return v
