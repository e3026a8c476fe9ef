"""Seed 002: the simplebot driven by /cmd_vel through the diff-drive controller, on the bus."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from robomodel.loading import load
from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg.types.geometry_msgs import Twist, Vector3
from robomodel.runtime.msg.types.nav_msgs import Odometry
from robomodel.runtime.msg.types.rosgraph_msgs import Clock
from robomodel.runtime.msg.types.sensor_msgs import LaserScan
from robomodel.sim import Placement, Simulation, read_world
from robomodel.sim.bus import SimBridge

from .conftest import SIMPLEBOT, SIMPLEBOT_LIDAR, SIMPLEBOT_YAML, WALL_WORLD

ON_GROUND = Placement(xyz_m=(0.0, 0.0, 0.076))


def _yaw(q) -> float:  # type: ignore[no-untyped-def]
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def test_simplebot_drives_one_metre_and_odometry_matches_ground_truth() -> None:
    context = Context(clock=ManualClock())
    sim = Simulation()
    sim.add_robot(load(str(SIMPLEBOT)), placement=ON_GROUND)
    sim.control(SIMPLEBOT_YAML, context=context)
    SimBridge(sim, context)
    got: dict[str, Odometry] = {}
    clocks: list[float] = []
    node = context.create_node("test")
    node.create_subscription(Odometry, "/simplebot_controller/odom", lambda m: got.update(odom=m))
    node.create_subscription(Odometry, "/ground_truth/odom", lambda m: got.update(truth=m))
    node.create_subscription(
        Clock, "/clock", lambda m: clocks.append(m.clock.sec + m.clock.nanosec * 1e-9)
    )
    pub = node.create_publisher(Twist, "/simplebot_controller/cmd_vel")
    sim.step(500)  # settle on the ground
    start = sim.data.body("base_link").xpos.copy()
    for _ in range(50):  # 5 s, commands at 10 Hz as `topic pub --rate 10`
        pub.publish(Twist(linear=Vector3(0.2, 0.0, 0.0)))
        sim.step(100)
    travelled = np.linalg.norm(sim.data.body("base_link").xpos[:2] - start[:2])
    assert travelled == pytest.approx(1.0, rel=0.05)
    odom, truth = got["odom"].pose.pose, got["truth"].pose.pose
    moved_truth = math.hypot(truth.position.x - start[0], truth.position.y - start[1])
    moved_odom = math.hypot(odom.position.x, odom.position.y)
    assert moved_odom == pytest.approx(moved_truth, rel=0.02)
    assert abs(_yaw(odom.orientation) - _yaw(truth.orientation)) < 0.02
    assert clocks[-1] == pytest.approx(sim.time_s, abs=0.011)
    assert all(b > a for a, b in itertools.pairwise(clocks))


def test_wall_two_metres_ahead_appears_in_the_laser_scan() -> None:
    context = Context(clock=ManualClock())
    sim = Simulation(read_world(WALL_WORLD))
    sim.add_robot(load(str(SIMPLEBOT_LIDAR)), placement=ON_GROUND)
    bridge = SimBridge(sim, context)
    scans: list[LaserScan] = []
    node = context.create_node("test")
    node.create_subscription(LaserScan, "/scan", scans.append)
    sim.step(1000)
    assert len(scans) == pytest.approx(10, abs=1)  # update_rate 10 Hz
    scan = scans[-1]
    assert len(scan.ranges) == 360 and scan.header.frame_id == "lidar_link"
    assert scan.angle_min == pytest.approx(-math.pi)
    assert scan.angle_increment == pytest.approx(2 * math.pi / 359)
    ahead = int(np.argmin(np.abs(scan.angle_min + scan.angle_increment * np.arange(360))))
    lidar_x = sim.data.site("lidar").xpos[0]
    assert lidar_x == pytest.approx(0.2, abs=0.01)
    assert scan.ranges[ahead] == pytest.approx(2.0 + 0.2 - lidar_x + 0.0, abs=0.02)
    assert scan.ranges[ahead] == pytest.approx(2.0, abs=0.02)
    behind = scan.ranges[0]
    assert behind == math.inf  # nothing within 3.5 m behind (REP-117)
    assert bridge.sensors[0].spec.topic == "/scan"


def test_simplebot_turns_at_the_commanded_rate() -> None:
    """Velocity joints are stiff servos: turning in place scrubs the wide wheels only a little."""
    from robomodel.sim.sensors.ground_truth import yaw_of

    context = Context(clock=ManualClock())
    sim = Simulation()
    sim.add_robot(load(str(SIMPLEBOT)), placement=ON_GROUND)
    sim.control(SIMPLEBOT_YAML, context=context)
    SimBridge(sim, context)
    pub = context.create_node("test").create_publisher(Twist, "/simplebot_controller/cmd_vel")
    sim.step(300)
    start = yaw_of(sim.data.body("base_link").xquat)
    for _ in range(20):
        pub.publish(Twist(angular=Vector3(0.0, 0.0, 0.5)))
        sim.step(100)
    turned = yaw_of(sim.data.body("base_link").xquat) - start
    assert turned == pytest.approx(1.0, rel=0.1)
