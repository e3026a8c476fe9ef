"""The simulator on the bus: /clock, sensors, ground truth and the gazebo-style services.

:class:`SimBridge` attaches a :class:`~robomodel.sim.engine.Simulation` to a runtime
:class:`~robomodel.runtime.Context`. Every ``1 / clock_rate_hz`` of sim time (before the
controller managers run) it publishes ``/clock``, moves a :class:`ManualClock` context to the
sim time (so timers and queued messages run deterministically, in order), and applies the
service requests received since the last tick. Sensors publish at their ``update_rate``
(every physics step for 0, as SDF), ground truth of floating robots
(``/<ns>/ground_truth/odom``, Odometry in the ``world`` frame) at ``ground_truth_rate_hz``.

It also publishes TF ``world -> <prefix>ground_truth`` (the true pose of
the root link) with the ground truth, and a latched ``/tf_static`` ``world -> <prefix>odom``
at the spawn pose, so a viewer with fixed frame ``world`` draws the robot where its odometry
says and the ground-truth frame where it really is (Gazebo's model vs. the odometry in RViz).

Services: pause, unpause, reset, step (single-stepping while paused, run by the owner's loop
via :attr:`SimBridge.pending_steps`), apply a body wrench and set a model's pose, with their
gazebo_msgs / std_srvs / ros_gz_interfaces types (see :mod:`robomodel.sim.bus_services`), under
the names of the graph's ROS version (``ros_version``): ROS 1's gazebo_ros names them
``/gazebo/...``, ROS 2's gazebo_ros ``/pause_physics``, ``/reset_world``, ...

Model and link states (:mod:`robomodel.sim.states`): ``/gazebo/model_states`` and
``/gazebo/link_states``, the get/set model and link state services and topics and
``/gazebo/get_model_properties`` (:mod:`robomodel.sim.state_services`), published by
:mod:`robomodel.sim.state_publishers`. On a ROS 1 graph each
states topic is published at every physics step while it has subscribers and not at all while
it has none, as gazebo_ros does (gazebo_ros_api_plugin.cpp, noetic-devel: the world-update
callback is connected on a topic's first subscriber and disconnected on its last). The callback
is gated by the publisher's cached ``get_subscription_count()``: a callback at every step makes
MuJoCo step one step at a time from Python instead of whole stretches between due callbacks
(:mod:`robomodel.sim.schedule`), so unsubscribed it must not run or break up the stretches
(bench/bench_states_rate.py: the UR5 at about 45x real time unsubscribed, 4-5x subscribed). On
a ROS 2 graph they come at 100 Hz, subscribed or not, as ROS 2's gazebo_ros_state publishes
them (gazebo_ros_state.cpp, ros2 branch: its ``update_rate`` default).
"""

from __future__ import annotations

import logging
import queue
import time
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from robomodel.description.rigid import quat_xyzw_from_rpy
from robomodel.runtime.clock import ManualClock
from robomodel.runtime.msg.types.builtin_interfaces import Time
from robomodel.runtime.msg.types.geometry_msgs import (
    Quaternion,
    Transform,
    TransformStamped,
    Vector3,
)
from robomodel.runtime.msg.types.rosgraph_msgs import Clock
from robomodel.runtime.msg.types.std_msgs import Header
from robomodel.runtime.msg.types.tf2_msgs import TFMessage
from robomodel.sim.build.robot import BuiltRobot
from robomodel.sim.build.scene import shape_body_name
from robomodel.sim.sensors.base import SimSensor
from robomodel.sim.sensors.contact import ContactSensor
from robomodel.sim.sensors.ground_truth import GroundTruth
from robomodel.sim.sensors.imu import ImuSensor
from robomodel.sim.sensors.lidar import Lidar
from robomodel.sim.sensors.spec import SensorKind, SensorSpec

if TYPE_CHECKING:
    from robomodel.runtime.context import Context
    from robomodel.sim.engine import Simulation
    from robomodel.sim.sensors.camera import Frame

__all__ = ["SimBridge", "robot_namespace"]

log = logging.getLogger("robomodel.sim")

_IDLE_CLOCK_PERIOD_S = 0.1  # /clock while paused [s of wall time]

_SENSORS: dict[SensorKind, type[SimSensor]] = {
    SensorKind.RAY: Lidar,
    SensorKind.SONAR: Lidar,
    SensorKind.IMU: ImuSensor,
    SensorKind.CONTACT: ContactSensor,
}


def robot_namespace(built: BuiltRobot) -> str:
    """``/`` for an unprefixed robot, ``/r1`` for prefix ``r1_`` or ``r1/``."""
    name = built.prefix.strip("/_")
    return f"/{name}" if name else "/"


class SimBridge:
    """Publishes the simulation on ``context`` (see the module docstring).

    Args:
        sim: The simulation (robots added; controllers may be added before or after).
        context: The bus.
        clock_rate_hz: /clock and bus-tick rate (Gazebo classic publishes /clock at 100 Hz
            by default, ROS 1 ``pub_clock_frequency``).
        ground_truth_rate_hz: Rate of the ground-truth odometry (0 disables it).
        node_name: The bridge's node (``gazebo``; a :class:`SimServer`, whose own node has
            that name, gives another).
        ros_version: Whose service names to offer: 1 (gazebo_ros's ``/gazebo/...``) or 2
            (also ROS 2 gazebo_ros's root-level names); None: 1 on a ROS 1 bus, else 2.
        model_names: Gazebo model name by robot prefix (a spawned robot's ``-model``); by
            default a robot's URDF name.
    """

    def __init__(
        self,
        sim: Simulation,
        context: Context,
        *,
        clock_rate_hz: float = 100.0,
        ground_truth_rate_hz: float = 50.0,
        node_name: str = "gazebo",
        ros_version: int | None = None,
        model_names: Mapping[str, str] | None = None,
    ) -> None:
        self.sim = sim
        self.context = context
        self.ros_version = ros_version or (1 if getattr(context, "bus", "") == "ros1" else 2)
        self._model_names = dict(model_names or {})
        self.paused = False
        self.pending_steps = 0
        self._last_idle_clock = 0.0
        self._requests: queue.SimpleQueue[Callable[[], None]] = queue.SimpleQueue()
        self.node = context.create_node(node_name)
        self._clock_pub = self.node.create_publisher(Clock, "/clock", 10)
        self._manual = isinstance(context.clock, ManualClock)
        # every attribute _tick reads exists before it is scheduled: a spawn served on another
        # thread builds a new bridge while the simulation keeps stepping
        self._wrench_ends: list[tuple[float, str, str]] = []
        sim.every(clock_rate_hz, self._tick, order=-1)
        self._static_pub: Any = None
        self._static: list[Any] = []
        self.sensors: list[SimSensor] = []
        self.ground_truth: list[GroundTruth] = []
        for built in sim.robots:
            self._add_robot(built, ground_truth_rate_hz)
        for i, mounted in enumerate(sim.world.sensors):  # the world's own (a camera on a pole)
            self._add_sensor(mounted.spec, "", "", 1000 + i, site=mounted.site)
        if ground_truth_rate_hz > 0:
            self._add_moving_shapes(ground_truth_rate_hz)
        self._add_states()
        from robomodel.sim.bus_services import bridge_services
        from robomodel.sim.state_services import state_services, state_topics

        self._unregister = [
            self.node.create_service(srv_type, name, handler).destroy
            for name, srv_type, handler in (*bridge_services(self), *state_services(self))
        ]
        for topic, msg_type, callback in state_topics(self):
            self.node.create_subscription(msg_type, topic, callback, 10)

    def model_name(self, built: BuiltRobot) -> str:
        """``built``'s Gazebo model name: as spawned, else its URDF name."""
        return self._model_names.get(built.prefix, built.robot.name)

    def _add_states(self) -> None:
        """/gazebo/model_states and /gazebo/link_states (see the module docstring)."""
        from robomodel.sim.state_publishers import publish_states
        from robomodel.sim.states import WorldStates

        self.states = WorldStates(self.sim, self.model_name)
        publish_states(self.sim, self.node, self.states, ros_version=self.ros_version)

    def _add_robot(self, built: BuiltRobot, ground_truth_rate_hz: float) -> None:
        sim = self.sim
        ns = robot_namespace(built)
        prefix_topic = "" if ns == "/" else ns
        for i, spec in enumerate(built.extensions.sensors):
            self._add_sensor(spec, built.prefix, prefix_topic, i)
        if ground_truth_rate_hz > 0 and built.floating:  # a welded base has no pose to report
            truth = GroundTruth(
                sim.model, sim.data, built.root_body, built.prefix + built.robot.tree().root
            )
            publisher = self.node.create_publisher(
                type(truth.measure(0.0)), f"{prefix_topic}/ground_truth/odom", 10
            )
            sim.every(ground_truth_rate_hz, _publishing(truth, publisher), order=1)
            self.ground_truth.append(truth)
            self._add_truth_tf(built, truth, ground_truth_rate_hz)
        elif not built.floating:
            self._add_weld_tf(built)

    def _add_sensor(
        self, spec: SensorSpec, prefix: str, prefix_topic: str, seed: int, site: str = ""
    ) -> None:
        """One sensor of a robot (frames prefixed ``prefix``, topics under ``prefix_topic``) or
        of the world (MuJoCo ``site``)."""
        if spec.camera is not None:
            self._add_camera(spec, prefix, prefix_topic, seed, site)
            return
        kind = _SENSORS[spec.kind]
        sensor = kind(spec, self.sim.model, self.sim.data, prefix=prefix, seed=seed, site=site)
        publisher = self.node.create_publisher(sensor.message_type, prefix_topic + spec.topic, 10)
        self.sim.every(spec.update_rate_hz, _publishing(sensor, publisher), order=1)
        self.sensors.append(sensor)

    def _add_camera(
        self, spec: SensorSpec, prefix: str, prefix_topic: str, seed: int, site: str
    ) -> None:
        """A camera or depth sensor: one render per update, published on every topic of its
        plugin (:mod:`robomodel.sim.sensors.camera`), ROS 1's queue of 2 as gazebo_ros."""
        from robomodel.sim.sensors.camera import CameraSensor
        from robomodel.sim.sensors.camera_spec import camera_topics

        assert spec.camera is not None
        topics = camera_topics(spec.camera, spec.name, self.ros_version)
        sensor = CameraSensor(
            spec, self.sim.model, self.sim.data, prefix=prefix, seed=seed, site=site, topics=topics
        )
        depth = 2 if self.ros_version == 1 else 5

        def advertise(msg_type: Any, topic: str) -> Any:
            return self.node.create_publisher(msg_type, prefix_topic + topic, depth)

        image = advertise(sensor.image_type, topics.image)
        info = advertise(sensor.info_type, topics.camera_info)
        extra: list[tuple[Any, Callable[[Frame], Any]]] = []
        if spec.camera.depth:
            extra = [
                (advertise(sensor.image_type, topics.depth_image), sensor.depth_image),
                (advertise(sensor.info_type, topics.depth_camera_info),
                 lambda frame: sensor.camera_info(frame.time_s)),
                (advertise(sensor.cloud_type, topics.points), sensor.points),
            ]  # fmt: skip

        def publish(time_s: float) -> None:
            frame = sensor.render(time_s)
            image.publish(sensor.image(frame))
            info.publish(sensor.camera_info(time_s))
            for publisher, build in extra:
                publisher.publish(build(frame))

        self.sim.every(spec.update_rate_hz, publish, order=1)
        self.sensors.append(sensor)

    def _add_moving_shapes(self, rate_hz: float) -> None:
        """TF ``world -> <model>_<i>`` for the world's objects that move (mass > 0), so that
        the viewer can draw them where the physics has them (static ones are in ``world``)."""
        frames = [
            shape_body_name(shape, i)
            for i, shape in enumerate(self.sim.world.shapes)
            if shape.mass_kg > 0
        ]
        if not frames:
            return
        truths = [(GroundTruth(self.sim.model, self.sim.data, f, f), f) for f in frames]
        tf_pub = self.node.create_publisher(TFMessage, "/tf", 100)

        def publish(time_s: float) -> None:
            tf_pub.publish(
                TFMessage([t for truth, f in truths for t in truth.transform(time_s, f).transforms])
            )

        self.sim.every(rate_hz, publish, order=1)

    def _add_weld_tf(self, built: BuiltRobot) -> None:
        """A robot welded where it was spawned: static ``world -> <root>`` at the spawn pose
        (none when its root link is ``world`` itself), so every robot hangs off ``world``."""
        root = built.prefix + built.robot.tree().root
        if root == "world":
            return
        x, y, z = built.placement.xyz_m
        qx, qy, qz, qw = quat_xyzw_from_rpy(*built.placement.rpy_rad)
        weld = TransformStamped(
            header=Header(frame_id="world"),
            child_frame_id=root,
            transform=Transform(Vector3(x, y, z), Quaternion(x=qx, y=qy, z=qz, w=qw)),
        )
        self._publish_static([weld])

    def _publish_static(self, transforms: list[Any]) -> None:
        from robomodel.runtime.qos import latched

        if self._static_pub is None:
            self._static_pub = self.node.create_publisher(TFMessage, "/tf_static", latched())
        self._static.extend(transforms)
        self._static_pub.publish(TFMessage(list(self._static)))

    def _add_truth_tf(self, built: BuiltRobot, truth: GroundTruth, rate_hz: float) -> None:
        tf_pub = self.node.create_publisher(TFMessage, "/tf", 100)
        frame = f"{built.prefix}ground_truth"
        self.sim.every(rate_hz, lambda t: tf_pub.publish(truth.transform(t, frame)), order=1)
        odom = truth.transform(0.0, f"{built.prefix}odom")
        origin = odom.transforms[0].transform
        x, y, z = built.placement.xyz_m
        origin.translation = Vector3(x, y, z)
        qx, qy, qz, qw = quat_xyzw_from_rpy(*built.placement.rpy_rad)
        origin.rotation = Quaternion(x=qx, y=qy, z=qz, w=qw)
        self._publish_static(list(odom.transforms))

    # -- the tick ------------------------------------------------------------------------------
    def poll(self) -> None:
        """While paused: apply queued service requests, run pending callbacks and keep
        publishing /clock (at most every 0.1 s of wall time) so that late subscribers
        (``topic echo /clock``, the viewer's status line) see the paused time."""
        while True:
            try:
                request = self._requests.get_nowait()
            except queue.Empty:
                break
            request()
        now = time.monotonic()
        if now - self._last_idle_clock >= _IDLE_CLOCK_PERIOD_S:
            self._last_idle_clock = now
            self._clock_pub.publish(Clock(clock=Time.from_seconds(self.sim.time_s)))
        self.context.spin_once(0.0)

    def _tick(self, time_s: float) -> None:
        self._end_wrenches(time_s)
        while True:
            try:
                request = self._requests.get_nowait()
            except queue.Empty:
                break
            request()
        self._clock_pub.publish(Clock(clock=Time.from_seconds(time_s)))
        if self._manual:
            dt = time_s - self.context.clock.now_s()
            if dt > 0:
                self.context.advance(dt)
            else:
                self.context.spin_once(0.0)

    # -- services ------------------------------------------------------------------------------
    def queue(self, action: Callable[[], None]) -> None:
        """Run ``action`` in the simulation loop, at its next tick (or poll while paused)."""
        self._requests.put(action)

    def apply_wrench(
        self,
        link: str,
        prefix: str,
        force_n: tuple[float, float, float],
        torque_nm: tuple[float, float, float],
        duration_s: float | None,
    ) -> None:
        """Apply a wrench (world frame, at the link's centre of mass) from the next tick on,
        for ``duration_s`` of sim time or, with None, until another one replaces it."""

        def apply() -> None:
            self.sim.apply_wrench(link, force_n=force_n, torque_nm=torque_nm, prefix=prefix)
            self._wrench_ends = [e for e in self._wrench_ends if e[1:] != (link, prefix)]
            if duration_s is not None:
                self._wrench_ends.append((self.sim.time_s + duration_s, link, prefix))

        self.queue(apply)

    def _end_wrenches(self, time_s: float) -> None:
        ended = [e for e in self._wrench_ends if e[0] <= time_s]
        if ended:
            self._wrench_ends = [e for e in self._wrench_ends if e[0] > time_s]
            for _, link, prefix in ended:
                self.sim.apply_wrench(link, prefix=prefix)

    def close(self) -> None:
        for unregister in self._unregister:
            unregister()
        self._unregister = []
        self.node.destroy()


def _publishing(source: Any, publisher: Any) -> Callable[[float], None]:
    def publish(time_s: float) -> None:
        publisher.publish(source.measure(time_s))

    return publish
