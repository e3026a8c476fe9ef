"""One URDF robot into a ``mujoco.MjSpec``: bodies, inertials, joints, geoms, mimic, sensors.

Every URDF link becomes a body (fixed-joint children are kept as joint-less bodies, so every
URDF frame still exists, unlike MuJoCo's URDF importer with ``fusestatic``); a root link other
than ``world`` gets a free joint (Gazebo spawns such a model floating), unless the model is
``<static>``. Names are prefixed with the robot's frame prefix.

Collisions follow Gazebo, not MuJoCo: links of one model do not collide with each other unless
one of them has ``<selfCollide>true`` (sdf link.sdf ``self_collide``, default false). Each robot
gets a collision bit: its geoms have ``contype = bit`` and ``conaffinity = ~bit``, so a robot
touches the world and the other robots but not itself; ``selfCollide`` links add a shared
bit to both masks.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from robomodel.description.model import Joint, JointType, Link, Origin, Robot
from robomodel.description.rigid import quat_wxyz_from_rpy, wxyz_from_xyzw
from robomodel.sim._mujoco import mujoco
from robomodel.sim.build.gazebo import GazeboExtensions, read_gazebo
from robomodel.sim.build.geoms import MeshLoader, geom_kwargs
from robomodel.sim.build.inertia import check_inertial, where
from robomodel.sim.build.joint_extras import JointExtras, read_joint_extras
from robomodel.sim.exceptions import SimulationError

__all__ = [
    "SELF_COLLIDE_BIT",
    "BuiltRobot",
    "Placement",
    "add_robot",
    "velocity_actuator_name",
]

SELF_COLLIDE_BIT = 1 << 30
_ALL_BITS = (1 << 31) - 1
_DEFAULT_TORSION, _DEFAULT_ROLL = 0.005, 0.0001  # MuJoCo's default friction[1:]


@dataclass(frozen=True, slots=True)
class Placement:
    """Where a robot is spawned (``spawn_entity -x -y -z -R -P -Y``) and its frame prefix."""

    prefix: str = ""
    xyz_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy_rad: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass
class BuiltRobot:
    """What :func:`add_robot` added, by (prefixed) MuJoCo name.

    Attributes:
        joints: URDF names of the movable (non-fixed) joints, in tree order.
        geom_friction: ``(geom name, sliding friction)`` for the min-combination rule.
    """

    robot: Robot
    placement: Placement
    extensions: GazeboExtensions
    root_body: str
    floating: bool
    joints: tuple[str, ...]
    geom_friction: list[tuple[str, float]] = field(default_factory=list)

    @property
    def prefix(self) -> str:
        return self.placement.prefix

    def body(self, link: str) -> str:
        """The MuJoCo body of URDF link ``link`` (``prefix + link``; a root ``world`` link
        becomes ``world_link``, since ``world`` is MuJoCo's own world body)."""
        name = self.placement.prefix + link
        return "world_link" if name == "world" else name

    def joint(self, name: str) -> str:
        return self.placement.prefix + name


def _quat_rpy(roll: float, pitch: float, yaw: float) -> list[float]:
    """MuJoCo's ``quat`` (wxyz) of URDF/SDF roll, pitch, yaw [rad]."""
    return list(quat_wxyz_from_rpy(roll, pitch, yaw))


def _quat(origin: Origin) -> list[float]:
    return list(wxyz_from_xyzw(origin.quaternion_xyzw()))


def _moving_groups(robot: Robot, static: bool) -> dict[str, bool]:
    """For each link: does it move (is it not welded to the world)?"""
    tree = robot.tree()
    moving: dict[str, bool] = {}
    root_moves = not static and tree.root != "world"
    moving[tree.root] = root_moves
    for _, joint in tree.walk():
        parent_moves = moving[joint.parent]
        moving[joint.child] = parent_moves or joint.type is not JointType.FIXED
    return moving


def _group_mass(robot: Robot, link: str) -> float:
    """Mass of ``link`` and the links welded to it by fixed joints (Gazebo's lumping)."""
    tree = robot.tree()
    inertial = robot.link(link).inertial
    total = inertial.mass_kg if inertial is not None else 0.0
    for child in tree.children(link):
        if tree.parent_joint[child].type is JointType.FIXED:
            total += _group_mass(robot, child)
    return total


def _check_inertials(robot: Robot, moving: dict[str, bool]) -> None:
    tree = robot.tree()
    for link in robot.links:
        if not moving.get(link.name, False):
            continue
        joint = tree.parent_joint.get(link.name)
        starts_group = joint is None or joint.type is not JointType.FIXED
        if starts_group and _group_mass(robot, link.name) <= 0.0:
            check_inertial(link, moving=True)  # raises with the link's file:line
        if link.inertial is not None and link.inertial.mass_kg != 0.0:
            check_inertial(link, moving=True)


def _set_inertial(body: Any, link: Link) -> None:
    inertial = link.inertial
    body.explicitinertial = True
    if inertial is None or inertial.mass_kg == 0.0:
        body.mass = 0.0
        body.ipos = [0.0, 0.0, 0.0]
        body.inertia = [0.0, 0.0, 0.0]
        return
    R = inertial.origin.matrix()[:3, :3]
    I_link = R @ np.asarray(inertial.inertia.matrix()) @ R.T
    body.mass = inertial.mass_kg
    body.ipos = list(inertial.origin.xyz_m)
    body.iquat = [1.0, 0.0, 0.0, 0.0]  # the tensor is already rotated into the link frame
    body.fullinertia = [
        I_link[0, 0], I_link[1, 1], I_link[2, 2], I_link[0, 1], I_link[0, 2], I_link[1, 2]
    ]  # fmt: skip


def _add_joint(body: Any, joint: Joint, name: str, extras: JointExtras | None = None) -> None:
    mj = mujoco()
    t = joint.type
    at = where(joint)
    if t is JointType.FLOATING:
        raise SimulationError(
            f"joint '{joint.name}' is floating below the root; MuJoCo allows free joints only "
            "on top-level bodies (make it the root or use a fixed joint)",
            where=at,
            name=joint.name,
        )
    if t is JointType.PLANAR:
        axis = np.asarray(joint.axis, dtype=float)
        axis /= np.linalg.norm(axis)
        u = np.cross(axis, [1.0, 0.0, 0.0] if abs(axis[0]) < 0.9 else [0.0, 1.0, 0.0])
        u /= np.linalg.norm(u)
        v = np.cross(axis, u)
        body.add_joint(name=f"{name}_x", type=mj.mjtJoint.mjJNT_SLIDE, axis=list(u))
        body.add_joint(name=f"{name}_y", type=mj.mjtJoint.mjJNT_SLIDE, axis=list(v))
        body.add_joint(name=name, type=mj.mjtJoint.mjJNT_HINGE, axis=list(axis))
        return
    kind = mj.mjtJoint.mjJNT_SLIDE if t is JointType.PRISMATIC else mj.mjtJoint.mjJNT_HINGE
    j = body.add_joint(name=name, type=kind, axis=list(joint.axis))
    limit = joint.limit
    if t is not JointType.CONTINUOUS and limit is not None:
        lo, hi = limit.lower_or_default, limit.upper_or_default
        if lo < hi:
            j.limited = mj.mjtLimited.mjLIMITED_TRUE
            j.range = [lo, hi]
    if limit is not None and limit.effort is not None and limit.effort > 0:
        j.actfrclimited = mj.mjtLimited.mjLIMITED_TRUE
        j.actfrcrange = [-limit.effort, limit.effort]
    if joint.dynamics is not None:
        j.damping = [joint.dynamics.damping or 0.0, 0.0, 0.0]
        j.frictionloss = joint.dynamics.friction or 0.0
    if extras is not None:
        j.armature = extras.armature
        j.stiffness = [extras.spring_stiffness, 0.0, 0.0]
        j.springref = extras.spring_reference


def add_robot(
    spec: Any,
    robot: Robot,
    *,
    placement: Placement,
    bit: int,
    loader: MeshLoader,
    include_visuals: bool = False,
) -> BuiltRobot:
    """Add ``robot`` to ``spec`` at ``placement`` with collision bit ``bit`` (see module doc).

    Raises:
        SimulationError: non-physical inertia, missing meshes, unsupported joints.
    """
    ext = read_gazebo(robot)
    moving = _moving_groups(robot, ext.static)
    _check_inertials(robot, moving)
    tree = robot.tree()
    built = BuiltRobot(robot, placement, ext, "", moving[tree.root], ())
    built.root_body = built.body(tree.root)
    bodies, joints = _add_bodies(spec, robot, built, read_joint_extras(robot))
    for link in robot.links:
        body = bodies[link.name]
        _set_inertial(body, link)
        if not ext.surface(link.name).gravity:
            body.gravcomp = 1.0
        _add_collisions(spec, body, link, built, bit, loader)
        if include_visuals:
            _add_visuals(spec, body, link, built, loader)
    _add_actuation(spec, robot, joints, placement.prefix)
    _add_sensor_sites(spec, ext, bodies, placement.prefix)
    built.joints = tuple(joints)
    return built


def _add_bodies(
    spec: Any, robot: Robot, built: BuiltRobot, extras: dict[str, JointExtras]
) -> tuple[dict[str, Any], list[str]]:
    """One body per link, placed by its joint's origin (the root at the placement, free unless
    fixed to the world); the movable joints' names in tree order."""
    tree = robot.tree()
    placement = built.placement
    root = spec.worldbody.add_body(
        name=built.root_body,
        pos=list(placement.xyz_m),
        quat=_quat_rpy(*placement.rpy_rad),
    )
    if built.floating:
        root.add_freejoint(name=placement.prefix + tree.root + "_free")
    bodies: dict[str, Any] = {tree.root: root}
    joints: list[str] = []
    for _, joint in tree.walk():
        body = bodies[joint.parent].add_body(
            name=built.body(joint.child), pos=list(joint.origin.xyz_m), quat=_quat(joint.origin)
        )
        bodies[joint.child] = body
        if joint.type is not JointType.FIXED:
            _add_joint(body, joint, placement.prefix + joint.name, extras.get(joint.name))
            joints.append(joint.name)
    return bodies, joints


def _add_actuation(spec: Any, robot: Robot, joints: list[str], prefix: str) -> None:
    """A velocity servo per driven joint; a mimic joint follows its leader by an equality."""
    mj = mujoco()
    for joint_name in joints:
        joint = robot.joint(joint_name)
        if joint.mimic is None and joint.type is not JointType.PLANAR:
            _add_velocity_servo(spec, joint, prefix)
        if joint.mimic is not None and joint.mimic.joint in joints:
            eq = spec.add_equality(
                type=mj.mjtEq.mjEQ_JOINT,
                name1=prefix + joint_name,
                name2=prefix + joint.mimic.joint,
            )
            eq.data[0:5] = [
                joint.mimic.offset_or_default,
                joint.mimic.multiplier_or_default,
                0,
                0,
                0,
            ]


def _add_sensor_sites(
    spec: Any, ext: GazeboExtensions, bodies: dict[str, Any], prefix: str
) -> None:
    """A site per Gazebo sensor at its pose; a camera sensor gets a MuJoCo camera too."""
    for sensor in ext.sensors:
        x, y, z, r, p, yaw = sensor.pose
        bodies[sensor.link].add_site(
            name=prefix + sensor.name, pos=[x, y, z], quat=_quat_rpy(r, p, yaw)
        )
        if sensor.camera is not None:
            from robomodel.sim.sensors.camera import add_mujoco_camera

            add_mujoco_camera(spec, bodies[sensor.link], prefix + sensor.name, sensor)


def velocity_actuator_name(joint: str) -> str:
    """The (prefixed) MuJoCo name of a joint's velocity servo."""
    return f"{joint}__velocity"


def _add_velocity_servo(spec: Any, joint: Joint, prefix: str) -> None:
    """A velocity servo, off (gain 0) until simulated hardware commands the joint's velocity.

    ``set_to_velocity``: force = kv (ctrl - qdot), clamped to the URDF effort limit as the ODE
    joint motor of gazebo_ros_control (``fmax`` = effort). The implicitfast integrator treats
    kv implicitly, so a stiff servo stays stable.
    """
    mj = mujoco()
    name = prefix + joint.name
    actuator = spec.add_actuator(
        name=velocity_actuator_name(name), target=name, trntype=mj.mjtTrn.mjTRN_JOINT
    )
    actuator.set_to_velocity(kv=0.0)
    limit = joint.limit
    if limit is not None and limit.effort is not None and limit.effort > 0:
        actuator.forcelimited = mj.mjtLimited.mjLIMITED_TRUE
        actuator.forcerange = [-limit.effort, limit.effort]


def _add_collisions(
    spec: Any, body: Any, link: Link, built: BuiltRobot, bit: int, loader: MeshLoader
) -> None:
    surface = built.extensions.surface(link.name)
    mu = surface.friction
    mu = 1.0 if mu is None else mu  # SDF surface.sdf default
    contype, conaffinity = bit, _ALL_BITS & ~bit
    if surface.self_collide:
        contype |= SELF_COLLIDE_BIT
        conaffinity |= SELF_COLLIDE_BIT
    for i, collision in enumerate(link.collisions):
        name = f"{built.prefix}{link.name}_collision" + (f"_{i}" if i else "")
        kwargs = geom_kwargs(spec, collision.geometry, loader, where(collision) or where(link))
        g = body.add_geom(
            name=name,
            pos=list(collision.origin.xyz_m),
            quat=_quat(collision.origin),
            **kwargs,
        )
        g.contype, g.conaffinity = contype, conaffinity
        g.friction = [mu, _DEFAULT_TORSION, _DEFAULT_ROLL]
        g.group = 3  # collision group; visuals are group 1 as in MuJoCo's URDF importer
        if surface.kp is not None and surface.kp > 0:
            g.solref = _solref(surface.kp, surface.kd or 1.0, link, spec.option.timestep)
        built.geom_friction.append((name, mu))


def _solref(kp: float, kd: float, link: Link, timestep: float) -> list[float]:
    """Gazebo ``kp``/``kd`` [N/m, N s/m] as MuJoCo ``(timeconst, dampratio)``.

    Uses the link's mass as the effective mass of the contact; the time constant is bounded
    below by 2 steps (MuJoCo's stability advice), the damping ratio to [0.1, 1].
    """
    mass = link.inertial.mass_kg if link.inertial is not None and link.inertial.mass_kg > 0 else 1.0
    omega = math.sqrt(kp / mass)
    ratio = kd / (2.0 * math.sqrt(kp * mass))
    return [max(2.0 * timestep, 1.0 / omega), min(1.0, max(0.1, ratio))]


def _add_visuals(spec: Any, body: Any, link: Link, built: BuiltRobot, loader: MeshLoader) -> None:
    rgba = built.extensions.surface(link.name).rgba
    for visual in link.visuals:
        kwargs = geom_kwargs(spec, visual.geometry, loader, where(visual) or where(link))
        g = body.add_geom(pos=list(visual.origin.xyz_m), quat=_quat(visual.origin), **kwargs)
        g.contype = g.conaffinity = 0
        g.group = 1
        g.density = 0.0
        colour = rgba or (visual.material.rgba if visual.material is not None else None)
        if colour is None and visual.material is not None and built.robot.materials:
            named = {m.name: m.rgba for m in built.robot.materials}
            colour = named.get(visual.material.name)
        if colour is not None:
            g.rgba = list(colour)
