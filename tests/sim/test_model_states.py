"""gazebo_ros's /gazebo/model_states and /gazebo/link_states, get/set model and link
state, get_model_properties, on a simulation server, with gazebo_ros's replies; the service
names of the graph's ROS version."""

from __future__ import annotations

import math
import time
from pathlib import Path

import pytest

from robomodel.description.packages import PackageIndex
from robomodel.loading import expand_description
from robomodel.runtime import Context
from robomodel.runtime.msg.types import gazebo_msgs as gz
from robomodel.runtime.msg.types.geometry_msgs import Point, Pose, Quaternion, Twist, Vector3
from robomodel.sim import default_world
from robomodel.sim.server import SimServer
from tests.conftest import EXAMPLES
from tests.timing import scaled

pytest.importorskip("mujoco")

UR5 = EXAMPLES / "ur5_description" / "urdf" / "ur5_robot.urdf.xacro"
SIMPLEBOT = EXAMPLES / "simplebot_description" / "urdf" / "simplebot.urdf.xacro"
UR5_LINKS = ["base_link", "shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link",
             "wrist_2_link", "wrist_3_link"]  # fmt: skip


def _xml(path: Path) -> str:
    return expand_description(path, package_index=PackageIndex()).urdf.decode()


def _server(ros_version: int) -> tuple[SimServer, Context]:
    context = Context()
    server = SimServer(
        default_world(), context=context, package_index=PackageIndex(), ros_version=ros_version
    )
    return server, context


def _call(context: Context, name: str, srv: object, request: object) -> object:
    return context.call_service(name, srv, request, timeout_s=scaled(5.0))  # type: ignore[arg-type]


def test_model_and_link_states_are_gazebo_s() -> None:
    """Seed 001's spawn_model -model robot -z 0.1: models ground_plane and robot, links
    model::link after Gazebo's fixed-joint lumping (no world, no ee_link), true poses."""
    server, context = _server(1)
    got: dict[str, object] = {}
    try:
        server.spawn("robot", _xml(UR5), xyz_m=(0.0, 0.0, 0.1))
        node = context.create_node("listener")
        for topic, kind in (("/gazebo/model_states", gz.ModelStates),
                            ("/gazebo/link_states", gz.LinkStates)):  # fmt: skip
            node.create_subscription(kind, topic, lambda m, t=topic: got.__setitem__(t, m), 10)
        server.drive(0.1)
        context.spin_once(0.0)
        models = got["/gazebo/model_states"]
        links = got["/gazebo/link_states"]
        assert models.name == ["ground_plane", "robot"]  # type: ignore[attr-defined]
        assert models.pose[1].position.z == pytest.approx(0.1)  # type: ignore[attr-defined]
        assert links.name == ["ground_plane::link"] + [f"robot::{n}" for n in UR5_LINKS]  # type: ignore[attr-defined]
        # shoulder_link sits d1 = 0.089159 above base_link, which is at the spawn height
        shoulder = links.pose[links.name.index("robot::shoulder_link")]  # type: ignore[attr-defined]
        assert shoulder.position.z == pytest.approx(0.1 + 0.089159, abs=1e-6)
    finally:
        server.close()
        context.shutdown()


def test_get_model_state_link_state_and_properties() -> None:
    server, context = _server(1)
    try:
        server.spawn("robot", _xml(UR5), xyz_m=(0.5, -0.25, 0.1))
        server.drive(0.05)
        reply = _call(context, "/gazebo/get_model_state", gz.GetModelState,
                      gz.GetModelState_Request("robot", ""))  # fmt: skip
        assert reply.success and reply.status_message == "GetModelState: got properties"  # type: ignore[attr-defined]
        p = reply.pose.position  # type: ignore[attr-defined]
        assert (p.x, p.y, p.z) == pytest.approx((0.5, -0.25, 0.1))
        missing = _call(context, "/gazebo/get_model_state", gz.GetModelState,
                        gz.GetModelState_Request("robott", ""))  # fmt: skip
        assert not missing.success  # type: ignore[attr-defined]
        assert missing.status_message == "GetModelState: model does not exist"  # type: ignore[attr-defined]
        relative = _call(
            context, "/gazebo/get_link_state", gz.GetLinkState,
            gz.GetLinkState_Request("robot::shoulder_link", "robot::base_link"),
        )  # fmt: skip
        assert relative.success, relative.status_message  # type: ignore[attr-defined]
        q = relative.link_state.pose.position  # type: ignore[attr-defined]
        assert (q.x, q.y, q.z) == pytest.approx((0.0, 0.0, 0.089159), abs=1e-6)
        props = _call(context, "/gazebo/get_model_properties", gz.GetModelProperties,
                      gz.GetModelProperties_Request("robot"))  # fmt: skip
        assert props.success and props.body_names == UR5_LINKS  # type: ignore[attr-defined]
        assert props.joint_names[0] == "world_joint"  # type: ignore[attr-defined]
        assert "shoulder_pan_joint" in props.joint_names  # type: ignore[attr-defined]
        assert "ee_fixed_joint" not in props.joint_names  # type: ignore[attr-defined]
    finally:
        server.close()
        context.shutdown()


def test_set_link_state_moves_a_free_body_and_refuses_a_jointed_link() -> None:
    server, context = _server(2)
    try:
        server.spawn("bot", _xml(SIMPLEBOT), xyz_m=(0.0, 0.0, 0.1))
        qz = math.sin(math.pi / 4)
        state = gz.LinkState(
            "bot::base_link", Pose(Point(2.0, 1.0, 0.5), Quaternion(0, 0, qz, qz)),
            Twist(Vector3(0.0, 0.0, 0.0)), "world",
        )  # fmt: skip
        reply = _call(context, "/gazebo/set_link_state", gz.SetLinkState,
                      gz.SetLinkState_Request(state))  # fmt: skip
        assert reply.success and reply.status_message == "SetLinkState: success"  # type: ignore[attr-defined]
        server.drive(0.02)  # applied at the next tick
        got = _call(context, "/gazebo/get_link_state", gz.GetLinkState,
                    gz.GetLinkState_Request("bot::base_link", ""))  # fmt: skip
        pose = got.link_state.pose  # type: ignore[attr-defined]
        assert (pose.position.x, pose.position.y) == pytest.approx((2.0, 1.0), abs=0.01)
        assert pose.orientation.z == pytest.approx(qz, abs=0.01)
        wheel = "bot::left_wheel"
        refused = _call(context, "/gazebo/set_link_state", gz.SetLinkState,
                        gz.SetLinkState_Request(gz.LinkState(wheel)))  # fmt: skip
        assert not refused.success and "hangs on a joint" in refused.status_message  # type: ignore[attr-defined]
    finally:
        server.close()
        context.shutdown()


@pytest.mark.parametrize("ros_version", [1, 2])
def test_service_names_follow_the_ros_version(ros_version: int) -> None:
    server, context = _server(ros_version)
    try:
        names = set(context.graph().services)
        ros1 = {"/gazebo/pause_physics", "/gazebo/get_model_state", "/gazebo/set_link_state",
                "/gazebo/get_link_state", "/gazebo/get_model_properties",
                "/gazebo/spawn_urdf_model"}  # fmt: skip
        ros2 = {"/pause_physics", "/unpause_physics", "/reset_world", "/reset_simulation",
                "/spawn_entity", "/delete_entity", "/get_model_list"}  # fmt: skip
        assert ros1 <= names
        assert (ros2 <= names) if ros_version == 2 else not (ros2 & names)
    finally:
        server.close()
        context.shutdown()


def test_the_set_model_state_topic_moves_the_model_as_the_service_does() -> None:
    server, context = _server(1)
    try:
        server.spawn("bot", _xml(SIMPLEBOT), xyz_m=(0.0, 0.0, 0.1))
        pub = context.create_node("teleop").create_publisher(
            gz.ModelState, "/gazebo/set_model_state", 10
        )
        pub.publish(gz.ModelState("bot", Pose(Point(-1.0, 3.0, 0.2), Quaternion(0, 0, 0, 1))))
        server.drive(0.05)  # the message is taken, then applied at the next tick
        server.drive(0.05)
        got = _call(context, "/gazebo/get_model_state", gz.GetModelState,
                    gz.GetModelState_Request("bot", "world"))  # fmt: skip
        p = got.pose.position  # type: ignore[attr-defined]
        assert (p.x, p.y) == pytest.approx((-1.0, 3.0), abs=0.01)
    finally:
        server.close()
        context.shutdown()


def _count_calls(monkeypatch: pytest.MonkeyPatch) -> dict[str, int]:
    """How often the bridge builds each states message (it publishes each one it builds)."""
    from robomodel.sim.states import WorldStates

    calls = {"model_states": 0, "link_states": 0}
    for name in calls:
        original = getattr(WorldStates, name)

        def counted(self: WorldStates, _name: str = name, _original: object = original) -> object:
            calls[_name] += 1
            return _original(self)  # type: ignore[operator]

        monkeypatch.setattr(WorldStates, name, counted)
    return calls


def _drain(context: Context) -> None:
    while context.spin_once(0.0):
        pass


def test_ros1_states_at_every_step_while_subscribed_and_none_without(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """gazebo_ros (gazebo_ros_api_plugin.cpp, noetic-devel): each topic is published at every
    world update from its first subscriber on, and not at all after its last one leaves."""
    calls = _count_calls(monkeypatch)
    server, context = _server(1)
    try:
        server.spawn("robot", _xml(UR5), xyz_m=(0.0, 0.0, 0.1))
        assert server.sim is not None
        sim = server.sim
        sim.step(100)
        assert calls == {"model_states": 0, "link_states": 0}
        got: list[object] = []
        sub = context.create_node("listener").create_subscription(
            gz.ModelStates, "/gazebo/model_states", got.append, 10
        )
        sim.step(100)
        _drain(context)
        assert calls == {"model_states": 100, "link_states": 0}  # link_states: nobody
        assert len(got) == 100
        sub.destroy()
        sim.step(100)
        assert calls == {"model_states": 100, "link_states": 0}
    finally:
        server.close()
        context.shutdown()


def test_ros2_states_at_gazebo_ros_state_s_100_hz(monkeypatch: pytest.MonkeyPatch) -> None:
    """ROS 2's gazebo_ros_state publishes at its ``update_rate`` (default 100 Hz), subscribed or
    not (gazebo_ros_state.cpp, ros2 branch)."""
    calls = _count_calls(monkeypatch)
    server, context = _server(2)
    try:
        server.spawn("robot", _xml(UR5), xyz_m=(0.0, 0.0, 0.1))
        assert server.sim is not None
        assert server.sim.timestep_s == pytest.approx(0.001)
        server.sim.step(100)  # 0.1 s
        assert calls == {"model_states": 10, "link_states": 10}
    finally:
        server.close()
        context.shutdown()


PUCK = """<robot name="puck"><link name="body">
  <inertial><origin xyz="0 0 0"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
</link></robot>"""


def test_states_carry_the_linear_and_angular_twist_in_the_world_frame() -> None:
    """gazebo_ros fills ModelStates/LinkStates twists with the link's world linear velocity,
    then its world angular velocity: a free body in the air keeps the twist it was set to (its
    spin about a principal axis exactly, its horizontal velocity; gravity changes only z)."""
    server, context = _server(1)
    got: dict[str, object] = {}
    try:
        server.spawn("puck", PUCK, xyz_m=(0.0, 0.0, 5.0))
        node = context.create_node("listener")
        for topic, kind in (("/gazebo/model_states", gz.ModelStates),
                            ("/gazebo/link_states", gz.LinkStates)):  # fmt: skip
            node.create_subscription(kind, topic, lambda m, t=topic: got.__setitem__(t, m), 10)
        state = gz.LinkState(
            "puck::body", Pose(Point(0.0, 0.0, 5.0), Quaternion(0, 0, 0, 1)),
            Twist(Vector3(0.3, -0.2, 0.0), Vector3(0.0, 0.0, 0.8)), "world",
        )  # fmt: skip
        reply = _call(context, "/gazebo/set_link_state", gz.SetLinkState,
                      gz.SetLinkState_Request(state))  # fmt: skip
        assert reply.success, reply.status_message  # type: ignore[attr-defined]
        server.drive(0.05)  # applied at the next tick
        got.clear()
        deadline = time.monotonic() + scaled(10.0)
        while len(got) < 2 and time.monotonic() < deadline:
            server.drive(0.02)
            context.spin_once(0.0)
        models, links = got["/gazebo/model_states"], got["/gazebo/link_states"]
        model_twist = models.twist[models.name.index("puck")]  # type: ignore[attr-defined]
        link_twist = links.twist[links.name.index("puck::body")]  # type: ignore[attr-defined]
        for twist in (model_twist, link_twist):
            lin, ang = twist.linear, twist.angular
            assert (lin.x, lin.y) == pytest.approx((0.3, -0.2), abs=1e-6)
            assert lin.z < -0.01  # falling
            assert (ang.x, ang.y, ang.z) == pytest.approx((0.0, 0.0, 0.8), abs=1e-6)
    finally:
        server.close()
        context.shutdown()
