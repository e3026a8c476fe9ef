"""diff_drive_controller (ros2_controllers, humble behaviour).

Parameters as the humble ``diff_drive_controller_parameter.yaml`` (see ``docs/control.md``).
Update order (humble ``DiffDriveController::update``): cmd_vel timeout → odometry (open loop
from the *unlimited* command, otherwise from the mean wheel feedback of each side) → odometry
and TF publication at ``publish_rate`` → speed limiter (jerk, acceleration, velocity) → wheel
velocity commands ``(v ∓ ω·ws/2) / r`` on every wheel of each side.
"""

from __future__ import annotations

import logging
import math
from typing import Any

from robomodel.control.controllers.base import (
    ControllerInterface,
    ControllerState,
    InterfaceConfiguration,
    ReturnType,
)
from robomodel.control.controllers.exceptions import ControllerError
from robomodel.control.controllers.odometry import Odometry
from robomodel.control.controllers.speed_limiter import SpeedLimiter
from robomodel.runtime.msg import (
    Header,
    Quaternion,
    TFMessage,
    Time,
    Transform,
    TransformStamped,
    Twist,
    TwistStamped,
    Vector3,
)
from robomodel.runtime.msg import (
    Odometry as OdometryMsg,
)
from robomodel.runtime.node import Publisher

__all__ = ["MAX_TWIST", "DiffDriveController"]

log = logging.getLogger("robomodel.control")
MAX_TWIST = 1e6  # [m/s] or [rad/s]: a bigger command is refused (see set_command)


def _time(t: float) -> Time:
    sec, nanosec = divmod(round(t * 1e9), 1_000_000_000)
    return Time(sec, nanosec)


def _yaw_quaternion(yaw_rad: float) -> Quaternion:
    return Quaternion(0.0, 0.0, math.sin(yaw_rad / 2.0), math.cos(yaw_rad / 2.0))


class DiffDriveController(ControllerInterface):
    """``diff_drive_controller/DiffDriveController`` (see the module docstring)."""

    type_name = "diff_drive_controller/DiffDriveController"

    def on_init(self) -> None:
        self._rejected = 0
        self.left_wheel_names = self.param_list("left_wheel_names", [])
        self.right_wheel_names = self.param_list("right_wheel_names", [])
        if not self.left_wheel_names or not self.right_wheel_names:
            raise ControllerError(
                f"controller '{self.name}': left_wheel_names and right_wheel_names are required"
            )
        if len(self.left_wheel_names) != len(self.right_wheel_names):
            raise ControllerError(
                f"controller '{self.name}': the number of left wheels "
                f"({len(self.left_wheel_names)}) and right wheels "
                f"({len(self.right_wheel_names)}) differ"
            )
        self.wheel_separation = self.param_float("wheel_separation", 0.0)
        self.wheel_radius = self.param_float("wheel_radius", 0.0)
        if bool(self.param("derive_wheel_params_from_urdf", False)):
            self._derive_wheel_params()
        if self.wheel_separation <= 0.0 or self.wheel_radius <= 0.0:
            raise ControllerError(
                f"controller '{self.name}': wheel_separation and wheel_radius must be > 0"
            )
        p = self.param_float
        self.wheel_separation_multiplier = p("wheel_separation_multiplier", 1.0)
        self.left_wheel_radius_multiplier = p("left_wheel_radius_multiplier", 1.0)
        self.right_wheel_radius_multiplier = p("right_wheel_radius_multiplier", 1.0)
        self.tf_frame_prefix_enable = bool(self.param("tf_frame_prefix_enable", True))
        self.tf_frame_prefix = str(self.param("tf_frame_prefix", ""))
        self.odom_frame_id = str(self.param("odom_frame_id", "odom"))
        self.base_frame_id = str(self.param("base_frame_id", "base_link"))
        self.pose_covariance_diagonal = [
            float(v) for v in self.param("pose_covariance_diagonal", [0.0] * 6)
        ]
        self.twist_covariance_diagonal = [
            float(v) for v in self.param("twist_covariance_diagonal", [0.0] * 6)
        ]
        for key in ("pose_covariance_diagonal", "twist_covariance_diagonal"):
            if len(getattr(self, key)) != 6:
                raise ControllerError(f"controller '{self.name}': {key} needs 6 values")
        self.open_loop = bool(self.param("open_loop", False))
        self.position_feedback = bool(self.param("position_feedback", True))
        self.enable_odom_tf = bool(self.param("enable_odom_tf", True))
        self.cmd_vel_timeout_s = p("cmd_vel_timeout", 0.5)
        self.publish_limited_velocity = bool(self.param("publish_limited_velocity", False))
        self.velocity_rolling_window_size = int(self.param("velocity_rolling_window_size", 10))
        self.use_stamped_vel = bool(self.param("use_stamped_vel", True))
        self.publish_rate_hz = p("publish_rate", 50.0)
        self.unstamped_topic = str(self.param("cmd_vel_unstamped_topic", "~/cmd_vel_unstamped"))
        self.limiter_linear = self._limiter("linear.x")
        self.limiter_angular = self._limiter("angular.z")
        self.odometry = Odometry(self.velocity_rolling_window_size)
        self._odom_pub: Publisher[OdometryMsg] | None = None
        self._tf_pub: Publisher[TFMessage] | None = None
        self._limited_pub: Publisher[TwistStamped] | None = None
        self._subs: list[Any] = []

    def _derive_wheel_params(self) -> None:
        """ROS 1 (RCS1 diff_drive_controller.cpp ``getWheelParams``): when not given, the
        separation is the x-y distance between the first left and right wheel joint origins and
        the radius that of the left wheel link's collision cylinder or sphere."""
        robot = self.robot
        if robot is None:
            return
        left, right = self.left_wheel_names[0], self.right_wheel_names[0]
        if not (robot.has_joint(left) and robot.has_joint(right)):
            return
        if self.wheel_separation <= 0.0:
            a = robot.joint(left).origin.matrix()[:3, 3]
            b = robot.joint(right).origin.matrix()[:3, 3]
            self.wheel_separation = math.hypot(a[0] - b[0], a[1] - b[1])
        if self.wheel_radius <= 0.0:
            link = robot.link(robot.joint(left).child)
            for collision in link.collisions:
                radius = getattr(collision.geometry, "radius_m", None)
                if radius is not None:
                    self.wheel_radius = float(radius)
                    break

    def _limiter(self, axis: str) -> SpeedLimiter:
        def num(key: str) -> float:
            v = self.param(f"{axis}.{key}", math.nan)
            return math.nan if v is None else float(v)

        return SpeedLimiter(
            has_velocity_limits=bool(self.param(f"{axis}.has_velocity_limits", False)),
            has_acceleration_limits=bool(self.param(f"{axis}.has_acceleration_limits", False)),
            has_jerk_limits=bool(self.param(f"{axis}.has_jerk_limits", False)),
            min_velocity=num("min_velocity"),
            max_velocity=num("max_velocity"),
            min_acceleration=num("min_acceleration"),
            max_acceleration=num("max_acceleration"),
            min_jerk=num("min_jerk"),
            max_jerk=num("max_jerk"),
        )

    # -- interfaces ---------------------------------------------------------------------------
    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual(
            [f"{w}/velocity" for w in (*self.left_wheel_names, *self.right_wheel_names)]
        )

    def state_interface_configuration(self) -> InterfaceConfiguration:
        kind = "position" if self.position_feedback else "velocity"
        return InterfaceConfiguration.individual(
            [f"{w}/{kind}" for w in (*self.left_wheel_names, *self.right_wheel_names)]
        )

    # -- lifecycle ----------------------------------------------------------------------------
    @property
    def frame_prefix(self) -> str:
        """humble: ``tf_frame_prefix``, or the node namespace when empty, with a trailing ``/``."""
        if not self.tf_frame_prefix_enable:
            return ""
        prefix = self.tf_frame_prefix
        if not prefix and self.node is not None:
            prefix = self.node.namespace
        prefix = prefix.strip("/") if prefix == "/" else prefix.lstrip("/")
        if prefix and not prefix.endswith("/"):
            prefix += "/"
        return prefix

    def on_configure(self) -> None:
        self.odometry = Odometry(self.velocity_rolling_window_size)
        self.odometry.set_wheel_params(
            self.wheel_separation * self.wheel_separation_multiplier,
            self.wheel_radius * self.left_wheel_radius_multiplier,
            self.wheel_radius * self.right_wheel_radius_multiplier,
        )
        self.reset_commands()
        self._publish_period_s = 1.0 / self.publish_rate_hz if self.publish_rate_hz > 0 else 0.0
        self._previous_publish_s: float | None = None
        node = self.node
        if node is None:
            return
        if self.use_stamped_vel:
            self._subs.append(
                node.create_subscription(TwistStamped, "~/cmd_vel", self._on_stamped, 10)
            )
        else:
            self._subs.append(
                node.create_subscription(Twist, self.unstamped_topic, self._on_unstamped, 10)
            )
        self._odom_pub = node.create_publisher(OdometryMsg, "~/odom", 10)
        if self.enable_odom_tf:
            self._tf_pub = node.create_publisher(TFMessage, "/tf", 100)
        if self.publish_limited_velocity:
            self._limited_pub = node.create_publisher(TwistStamped, "~/cmd_vel_out", 10)

    def on_cleanup(self) -> None:
        for sub in self._subs:
            sub.destroy()
        self._subs = []
        for pub in (self._odom_pub, self._tf_pub, self._limited_pub):
            if pub is not None:
                pub.destroy()
        self._odom_pub = self._tf_pub = self._limited_pub = None

    def reset_commands(self) -> None:
        self._rejected = 0
        self.command = (0.0, 0.0, -math.inf)  # (v [m/s], ω [rad/s], stamp [s])
        self.previous_commands = [(0.0, 0.0), (0.0, 0.0)]  # front (older), back (newer)
        self._now_s = 0.0

    def on_activate(self) -> None:
        n = len(self.left_wheel_names)
        self._left_cmd = self.command_interfaces[:n]
        self._right_cmd = self.command_interfaces[n:]
        self._left_state = self.state_interfaces[:n]
        self._right_state = self.state_interfaces[n:]
        self.odometry.reset_odometry()
        self._first = True

    def on_deactivate(self) -> None:
        for ci in self.command_interfaces:
            ci.set(0.0)  # humble halt(): wheels to zero velocity

    # -- commands -----------------------------------------------------------------------------
    def set_command(
        self, linear_m_s: float, angular_rad_s: float, stamp_s: float | None = None
    ) -> None:
        """A twist command; ``stamp_s`` None or 0 means "now" (zero stamps are accepted).

        A non-finite command, or one beyond ``MAX_TWIST`` (1e6 m/s or rad/s: no robot drives
        that fast, and such a value makes the simulator's actuators overflow), is refused with
        a warning (at the 1st, 2nd, 4th, 8th ... refusal) and the last good command is held,
        as the position controllers do.
        """
        if not (abs(linear_m_s) <= MAX_TWIST and abs(angular_rad_s) <= MAX_TWIST):
            self._rejected += 1
            if self._rejected & (self._rejected - 1) == 0:
                log.warning(
                    "%s: cmd_vel (linear.x %r, angular.z %r) is not finite or beyond %g; the "
                    "last good command is held (%d times)",
                    self.name,
                    linear_m_s,
                    angular_rad_s,
                    MAX_TWIST,
                    self._rejected,
                )
            return
        stamp = stamp_s if stamp_s else self._now_s
        self.command = (linear_m_s, angular_rad_s, stamp)

    def _on_stamped(self, msg: Any) -> None:
        self.set_command(msg.twist.linear.x, msg.twist.angular.z, msg.header.stamp.to_seconds())

    def _on_unstamped(self, msg: Any) -> None:
        self.set_command(msg.linear.x, msg.angular.z, None)

    # -- the cycle ----------------------------------------------------------------------------
    def update(self, time_s: float, period_s: float) -> ReturnType:
        if self.state is not ControllerState.ACTIVE:
            return ReturnType.OK
        self._now_s = time_s
        if self._first:
            self._first = False
            self.odometry.init(time_s)
            self._previous_publish_s = time_s
        v, w, stamp = self.command
        if self.cmd_vel_timeout_s > 0.0 and time_s - stamp > self.cmd_vel_timeout_s:
            v = w = 0.0
            self.command = (0.0, 0.0, stamp)
        odom = self.odometry
        if self.open_loop:
            odom.update_open_loop(v, w, time_s)
        else:
            left = sum(si.get() for si in self._left_state) / len(self._left_state)
            right = sum(si.get() for si in self._right_state) / len(self._right_state)
            if math.isnan(left) or math.isnan(right):
                return ReturnType.ERROR
            if self.position_feedback:
                odom.update(left, right, time_s)
            else:
                odom.update_from_velocity(
                    left * odom.left_wheel_radius * period_s,
                    right * odom.right_wheel_radius * period_s,
                    time_s,
                )
        self._maybe_publish(time_s)
        (v1, w1), (v0, w0) = self.previous_commands  # front = one before, back = previous
        v = self.limiter_linear.limit(v, v0, v1, period_s)
        w = self.limiter_angular.limit(w, w0, w1, period_s)
        self.previous_commands = [(v0, w0), (v, w)]
        if self._limited_pub is not None:
            self._limited_pub.publish(
                TwistStamped(
                    Header(_time(time_s)), Twist(Vector3(v, 0.0, 0.0), Vector3(0.0, 0.0, w))
                )
            )
        ws = odom.wheel_separation
        left_cmd = (v - w * ws / 2.0) / odom.left_wheel_radius
        right_cmd = (v + w * ws / 2.0) / odom.right_wheel_radius
        for ci in self._left_cmd:
            ci.set(left_cmd)
        for ci in self._right_cmd:
            ci.set(right_cmd)
        return ReturnType.OK

    def _maybe_publish(self, time_s: float) -> None:
        assert self._previous_publish_s is not None  # set on the first update
        if self._previous_publish_s + self._publish_period_s >= time_s:
            return
        self._previous_publish_s += self._publish_period_s  # humble: by the publish period
        if self._odom_pub is None and self._tf_pub is None:
            return
        odom = self.odometry
        prefix = self.frame_prefix
        header = Header(_time(time_s), prefix + self.odom_frame_id)
        q = _yaw_quaternion(odom.heading)
        if self._odom_pub is not None:
            msg = OdometryMsg(header=header, child_frame_id=prefix + self.base_frame_id)
            msg.pose.pose.position.x = odom.x
            msg.pose.pose.position.y = odom.y
            msg.pose.pose.orientation = q
            msg.twist.twist.linear.x = odom.linear
            msg.twist.twist.angular.z = odom.angular
            for k in range(6):
                msg.pose.covariance[7 * k] = self.pose_covariance_diagonal[k]
                msg.twist.covariance[7 * k] = self.twist_covariance_diagonal[k]
            self._odom_pub.publish(msg)
        if self._tf_pub is not None:
            tf = TransformStamped(
                Header(_time(time_s), prefix + self.odom_frame_id),
                prefix + self.base_frame_id,
                Transform(Vector3(odom.x, odom.y, 0.0), q),
            )
            self._tf_pub.publish(TFMessage([tf]))
