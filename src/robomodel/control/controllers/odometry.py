"""Differential-drive odometry and the rolling mean (ros2_controllers diff_drive_controller, humble).

odometry.cpp: ``update(left_pos, right_pos, t)`` turns wheel angles into metres travelled and
calls ``update_from_velocity``; the pose is integrated with ``integrate_exact`` (second-order
Runge–Kutta when the heading change is below 1e-6, otherwise the exact arc); velocities are
rolling means (``rcppmath::RollingMeanAccumulator``) of the per-update increments divided by dt.
"""

from __future__ import annotations

import math

__all__ = ["Odometry", "RollingMean"]


class RollingMean:
    """Ring buffer of ``window`` values; mean over the values seen so far (at most ``window``)."""

    __slots__ = ("_buffer", "_index", "_sum", "filled", "window")

    def __init__(self, window: int) -> None:
        self.window = max(1, int(window))
        self._buffer = [0.0] * self.window
        self._index = 0
        self._sum = 0.0
        self.filled = 0

    def accumulate(self, value: float) -> None:
        self._sum += value - self._buffer[self._index]
        self._buffer[self._index] = value
        self._index = (self._index + 1) % self.window
        self.filled = min(self.filled + 1, self.window)

    def mean(self) -> float:
        return self._sum / self.filled if self.filled else 0.0


class Odometry:
    """Pose (x, y, heading) and rolling-mean velocities of a differential drive.

    Args:
        velocity_rolling_window_size: Window of the velocity means (default 10).
    """

    def __init__(self, velocity_rolling_window_size: int = 10) -> None:
        self.window = velocity_rolling_window_size
        self.wheel_separation = 1.0
        self.left_wheel_radius = 1.0
        self.right_wheel_radius = 1.0
        self.reset_odometry()
        self.timestamp_s = 0.0

    def set_wheel_params(
        self, separation_m: float, left_radius_m: float, right_radius_m: float
    ) -> None:
        self.wheel_separation = separation_m
        self.left_wheel_radius = left_radius_m
        self.right_wheel_radius = right_radius_m

    def init(self, time_s: float) -> None:
        self._reset_accumulators()
        self.timestamp_s = time_s

    def reset_odometry(self) -> None:
        self.x = 0.0
        self.y = 0.0
        self.heading = 0.0
        self.linear = 0.0
        self.angular = 0.0
        self.left_wheel_old_pos = 0.0
        self.right_wheel_old_pos = 0.0
        self._reset_accumulators()

    def _reset_accumulators(self) -> None:
        self._linear_acc = RollingMean(self.window)
        self._angular_acc = RollingMean(self.window)

    def update(self, left_pos_rad: float, right_pos_rad: float, time_s: float) -> bool:
        """From wheel angles; ``False`` (nothing done) when ``dt < 1e-4`` s."""
        dt = time_s - self.timestamp_s
        if dt < 0.0001:
            return False
        left = left_pos_rad * self.left_wheel_radius
        right = right_pos_rad * self.right_wheel_radius
        left_dist, right_dist = left - self.left_wheel_old_pos, right - self.right_wheel_old_pos
        self.left_wheel_old_pos, self.right_wheel_old_pos = left, right
        return self.update_from_velocity(left_dist, right_dist, time_s)

    def update_from_velocity(self, left_m: float, right_m: float, time_s: float) -> bool:
        """From the distances [m] the wheels travelled since the last update. An update at
        the time of the last one (the first after :meth:`init`) moves the pose but gives no
        velocity (odometry.cpp would divide by zero and keep NaN in its rolling means)."""
        dt = time_s - self.timestamp_s
        linear = (left_m + right_m) * 0.5
        angular = (right_m - left_m) / self.wheel_separation
        self.integrate_exact(linear, angular)
        self.timestamp_s = time_s
        if dt <= 0.0:
            return True
        self._linear_acc.accumulate(linear / dt)
        self._angular_acc.accumulate(angular / dt)
        self.linear = self._linear_acc.mean()
        self.angular = self._angular_acc.mean()
        return True

    def update_open_loop(self, linear_m_s: float, angular_rad_s: float, time_s: float) -> None:
        """Dead reckoning from the commanded velocities (no rolling mean)."""
        self.linear = linear_m_s
        self.angular = angular_rad_s
        dt = time_s - self.timestamp_s
        self.timestamp_s = time_s
        self.integrate_exact(linear_m_s * dt, angular_rad_s * dt)

    def integrate_runge_kutta2(self, linear_m: float, angular_rad: float) -> None:
        direction = self.heading + angular_rad * 0.5
        self.x += linear_m * math.cos(direction)
        self.y += linear_m * math.sin(direction)
        self.heading += angular_rad

    def integrate_exact(self, linear_m: float, angular_rad: float) -> None:
        if abs(angular_rad) < 1e-6:
            self.integrate_runge_kutta2(linear_m, angular_rad)
        else:
            heading_old = self.heading
            r = linear_m / angular_rad
            self.heading += angular_rad
            self.x += r * (math.sin(self.heading) - math.sin(heading_old))
            self.y += -r * (math.cos(self.heading) - math.cos(heading_old))
