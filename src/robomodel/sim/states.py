"""Gazebo's models and links in a MuJoCo scene, with their true poses and twists: what
gazebo_ros publishes on ``/gazebo/model_states`` and ``/gazebo/link_states`` and answers to
``get_model_state`` / ``get_link_state`` / ``get_model_properties``.

The models are Gazebo's, in its order: the world's (``ground_plane``, then the SDF models of the
world file and those spawned with ``-sdf``), then the spawned robots. A robot's links are the
ones Gazebo keeps after sdformat's fixed-joint lumping (its root link, unless that is
``world``, and every child of a non-fixed joint or of the ``world`` link), named
``model::link``; its joints are the non-fixed ones and those to ``world``. A model's pose is its
model frame: a robot's root body (where it was spawned, or where its floating base is). An SDF
model of the world is one link, ``model::link`` (Gazebo's default link name); a static one is at
its first collision's pose (robomodel keeps collision poses, not the model frame).

Twists are Gazebo's: the linear velocity of the frame's origin and the angular velocity, both
in the world frame (MuJoCo's ``mj_objectVelocity`` in world orientation).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from robomodel.description.model import JointType
from robomodel.runtime.msg.types.geometry_msgs import Point, Pose, Quaternion, Twist, Vector3
from robomodel.sim._mujoco import mujoco

if TYPE_CHECKING:
    from collections.abc import Callable

    from robomodel.sim.build.robot import BuiltRobot
    from robomodel.sim.engine import Simulation

__all__ = ["Entity", "ModelInfo", "WorldStates", "gazebo_links"]

_IDENTITY_WXYZ = (1.0, 0.0, 0.0, 0.0)


@dataclass(frozen=True, slots=True)
class Entity:
    """A model frame or a link: a MuJoCo body, or (``body`` None) a fixed pose."""

    name: str  # "robot" or "robot::base_link"
    body: int | None
    xyz_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    quat_wxyz: tuple[float, float, float, float] = _IDENTITY_WXYZ


@dataclass(frozen=True, slots=True)
class ModelInfo:
    """One Gazebo model (``get_model_properties``)."""

    name: str
    frame: Entity
    links: tuple[Entity, ...]
    joints: tuple[str, ...] = ()
    geoms: tuple[str, ...] = ()
    is_static: bool = False


def gazebo_links(built: BuiltRobot) -> tuple[list[str], list[str]]:
    """The URDF links Gazebo keeps after fixed-joint lumping, and its joints (module docstring)."""
    tree = built.robot.tree()
    root = tree.root
    links = [] if root == "world" else [root]
    joints = []
    for _, joint in tree.walk():
        if joint.type is not JointType.FIXED or joint.parent == "world":
            links.append(joint.child)
            joints.append(joint.name)
    return links, joints


class WorldStates:
    """The models of ``sim`` (see the module docstring).

    Args:
        sim: The built simulation.
        model_name: A robot's Gazebo model name (the name it was spawned as).
    """

    def __init__(self, sim: Simulation, model_name: Callable[[BuiltRobot], str]) -> None:
        self.sim = sim
        self._velocity = np.zeros(6)
        self._body_type = int(mujoco().mjtObj.mjOBJ_BODY)
        self.models: list[ModelInfo] = []
        if sim.world.ground_plane:
            ground = Entity("ground_plane", None)
            self.models.append(
                ModelInfo("ground_plane", ground, (Entity("ground_plane::link", None),),
                          geoms=("collision",), is_static=True)
            )  # fmt: skip
        self._add_world_models()
        for built in sim.robots:
            self._add_robot(built, model_name(built))
        self._by_name = {m.name: m for m in self.models}
        self._links = {link.name: link for m in self.models for link in m.links}

    def _add_world_models(self) -> None:
        from robomodel.description.rigid import quat_wxyz_from_rpy
        from robomodel.sim.build.scene import shape_body_name

        seen: dict[str, list[Entity]] = {}
        static: dict[str, bool] = {}
        for i, shape in enumerate(self.sim.world.shapes):
            if shape.model in seen:
                continue
            if shape.mass_kg > 0:
                body = self._body(shape_body_name(shape, i))
                frame = Entity(shape.model, body)
            else:
                x, y, z, roll, pitch, yaw = shape.pose
                w, qx, qy, qz = quat_wxyz_from_rpy(roll, pitch, yaw)
                frame = Entity(shape.model, None, (x, y, z), (w, qx, qy, qz))
            seen[shape.model] = [frame]
            static[shape.model] = shape.mass_kg <= 0
        for model, (frame,) in seen.items():
            link = Entity(f"{model}::link", frame.body, frame.xyz_m, frame.quat_wxyz)
            self.models.append(ModelInfo(model, frame, (link,), is_static=static[model]))

    def _add_robot(self, built: BuiltRobot, name: str) -> None:
        links, joints = gazebo_links(built)
        entities = tuple(Entity(f"{name}::{link}", self._body(built.body(link))) for link in links)
        mj = mujoco()
        model = self.sim.model
        bodies = {e.body for e in entities}
        geoms = tuple(
            mj.mj_id2name(model, mj.mjtObj.mjOBJ_GEOM, g).removeprefix(built.prefix)
            for g in range(model.ngeom)
            if int(model.geom_bodyid[g]) in bodies and mj.mj_id2name(model, mj.mjtObj.mjOBJ_GEOM, g)
        )
        frame = Entity(name, self._body(built.root_body))
        self.models.append(
            ModelInfo(name, frame, entities, tuple(joints), geoms, built.extensions.static)
        )

    def _body(self, name: str) -> int:
        return int(self.sim.model.body(name).id)

    # -- lookups ------------------------------------------------------------------------------
    def model(self, name: str) -> ModelInfo | None:
        return self._by_name.get(name)

    def entity(self, name: str) -> Entity | None:
        """A model or link by Gazebo's ``EntityByName``: a model name, a scoped link name, or
        a link's own name (the first model's that has it)."""
        found = self._by_name.get(name)
        if found is not None:
            return found.frame
        if name in self._links:
            return self._links[name]
        for link_name, link in self._links.items():
            if link_name.rsplit("::", 1)[-1] == name:
                return link
        return None

    # -- values -------------------------------------------------------------------------------
    def pose_twist(self, entity: Entity) -> tuple[Pose, Twist]:
        """``entity``'s pose and twist in the world frame."""
        if entity.body is None:
            w, x, y, z = entity.quat_wxyz
            return Pose(Point(*entity.xyz_m), Quaternion(x, y, z, w)), Twist()
        d = self.sim.data
        px, py, pz = (float(v) for v in d.xpos[entity.body])
        w, x, y, z = (float(v) for v in d.xquat[entity.body])
        mujoco().mj_objectVelocity(
            self.sim.model, d, self._body_type, entity.body, self._velocity, 0
        )
        wx, wy, wz, vx, vy, vz = (float(v) for v in self._velocity)
        return Pose(Point(px, py, pz), Quaternion(x, y, z, w)), Twist(
            Vector3(vx, vy, vz), Vector3(wx, wy, wz)
        )

    def states(self, entities: list[Entity]) -> tuple[list[str], list[Pose], list[Twist]]:
        names, poses, twists = [], [], []
        for entity in entities:
            pose, twist = self.pose_twist(entity)
            names.append(entity.name)
            poses.append(pose)
            twists.append(twist)
        return names, poses, twists

    def model_states(self) -> Any:
        from robomodel.runtime.msg.types.gazebo_msgs import ModelStates

        return ModelStates(*self.states([m.frame for m in self.models]))

    def link_states(self) -> Any:
        from robomodel.runtime.msg.types.gazebo_msgs import LinkStates

        return LinkStates(*self.states([link for m in self.models for link in m.links]))

    def relative(self, entity: Entity, frame: Entity) -> tuple[Pose, Twist]:
        """``entity``'s pose in ``frame`` and its twist relative to ``frame``, in ``frame``'s
        axes (gazebo_ros's ``model_pose - frame_pose`` and ``RotateVectorReverse``)."""
        from robomodel.kinematics.se3 import matrix_from_quat_xyzw, quat_xyzw_from_matrix

        pose, twist = self.pose_twist(entity)
        ref_pose, ref_twist = self.pose_twist(frame)
        R_world_frame = matrix_from_quat_xyzw(_xyzw(ref_pose.orientation))
        R_world_entity = matrix_from_quat_xyzw(_xyzw(pose.orientation))
        p = R_world_frame.T @ (_vec(pose.position) - _vec(ref_pose.position))
        qx, qy, qz, qw = quat_xyzw_from_matrix(R_world_frame.T @ R_world_entity).tolist()
        v = R_world_frame.T @ (_vec(twist.linear) - _vec(ref_twist.linear))
        w = R_world_frame.T @ (_vec(twist.angular) - _vec(ref_twist.angular))
        return Pose(Point(*p.tolist()), Quaternion(qx, qy, qz, qw)), Twist(
            Vector3(*v.tolist()), Vector3(*w.tolist())
        )


def _vec(v: Any) -> np.ndarray:
    return np.array([v.x, v.y, v.z])


def _xyzw(q: Quaternion) -> np.ndarray:
    return np.array([q.x, q.y, q.z, q.w])
