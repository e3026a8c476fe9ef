"""A whole scene: the world's ground, light and shapes plus the robots, compiled together."""

from __future__ import annotations

from typing import Any

from robomodel.description.rigid import quat_wxyz_from_rpy
from robomodel.sim._mujoco import mujoco
from robomodel.sim.build.robot import BuiltRobot
from robomodel.sim.world import Shape, ShapeKind, World, WorldSensor

__all__ = ["WORLD_BIT", "add_world", "apply_min_friction", "new_spec", "shape_body_name"]

WORLD_BIT = 1
_ALL_BITS = (1 << 31) - 1


def new_spec(world: World) -> Any:
    """An ``MjSpec`` with the world's physics options (radians, no inertia from geoms)."""
    mj = mujoco()
    spec = mj.MjSpec()
    spec.modelname = world.name
    spec.compiler.degree = False  # MjSpec's default is degrees for hinge ranges
    spec.compiler.autolimits = True
    spec.compiler.inertiafromgeom = mj.mjtInertiaFromGeom.mjINERTIAFROMGEOM_FALSE
    spec.option.timestep = world.timestep_s
    spec.option.gravity = list(world.gravity)
    # implicitfast: stable with stiff joint damping; MuJoCo's recommended integrator.
    spec.option.integrator = mj.mjtIntegrator.mjINT_IMPLICITFAST
    return spec


def add_world(spec: Any, world: World) -> None:
    """Ground plane (Gazebo's ground_plane: mu 100), sun and the world's shapes."""
    mj = mujoco()
    g = mj.mjtGeom
    if world.ground_plane:
        plane = spec.worldbody.add_geom(
            name="ground_plane", type=g.mjGEOM_PLANE, size=[0, 0, 1], rgba=[0.8, 0.8, 0.8, 1]
        )
        plane.friction = [world.ground_friction, 0.005, 0.0001]
        _world_bits(plane)
    if world.sun:
        spec.worldbody.add_light(name="sun", pos=[0, 0, 10], dir=[0.5, 0.1, -0.9])
    for i, shape in enumerate(world.shapes):
        _add_shape(spec, shape, i)
    for sensor in world.sensors:
        _add_sensor_mount(spec, sensor)


def _add_sensor_mount(spec: Any, sensor: WorldSensor) -> None:
    """A world sensor's link as a static body of its own (not the world body, which a ray
    sensor would exclude whole), with the sensor's site (and camera) on it."""
    x, y, z, r, p, yaw = sensor.link_pose
    body = spec.worldbody.add_body(
        name=sensor.site, pos=[x, y, z], quat=quat_wxyz_from_rpy(r, p, yaw)
    )
    sx, sy, sz, sr, sp, syaw = sensor.spec.pose
    body.add_site(name=sensor.site, pos=[sx, sy, sz], quat=quat_wxyz_from_rpy(sr, sp, syaw))
    if sensor.spec.camera is not None:
        from robomodel.sim.sensors.camera import add_mujoco_camera

        add_mujoco_camera(spec, body, sensor.site, sensor.spec)


def shape_body_name(shape: Shape, index: int) -> str:
    """The MuJoCo body (and TF frame) name of the world's shape number ``index``."""
    return f"{shape.model}_{index}"


def _world_bits(geom: Any) -> None:
    geom.contype, geom.conaffinity = WORLD_BIT, _ALL_BITS


def _add_shape(spec: Any, shape: Shape, index: int) -> None:
    mj = mujoco()
    g = mj.mjtGeom
    x, y, z, r, p, yaw = shape.pose
    parent = spec.worldbody
    name = shape_body_name(shape, index)
    pos, quat = [x, y, z], list(quat_wxyz_from_rpy(r, p, yaw))
    if shape.mass_kg > 0:
        parent = spec.worldbody.add_body(name=name, pos=pos, quat=quat)
        parent.add_freejoint()
        pos, quat = [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]
    sx, sy, sz = shape.size
    kind, size = {
        ShapeKind.BOX: (g.mjGEOM_BOX, [sx / 2, sy / 2, sz / 2]),
        ShapeKind.CYLINDER: (g.mjGEOM_CYLINDER, [sx, sy / 2, 0]),
        ShapeKind.SPHERE: (g.mjGEOM_SPHERE, [sx, 0, 0]),
        ShapeKind.PLANE: (g.mjGEOM_PLANE, [sx, sy, 1]),
    }[shape.kind]
    geom = parent.add_geom(
        name=f"{name}_geom", type=kind, size=size, pos=pos, quat=quat, rgba=list(shape.rgba)
    )
    geom.friction = [shape.friction, 0.005, 0.0001]
    if shape.mass_kg > 0:
        parent.explicitinertial = True
        parent.ipos = [0.0, 0.0, 0.0]  # the centre of the shape (else it is not initialised)
        parent.iquat = [1.0, 0.0, 0.0, 0.0]
        parent.mass = shape.mass_kg
        parent.fullinertia = [*_moments(shape), 0.0, 0.0, 0.0]
    _world_bits(geom)


def _moments(shape: Shape) -> tuple[float, float, float]:
    """Principal moments of a solid box, cylinder or sphere [kg m^2]."""
    m = shape.mass_kg
    a, b, c = shape.size
    if shape.kind is ShapeKind.BOX:
        return (m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12)
    if shape.kind is ShapeKind.CYLINDER:
        side = m * (3 * a * a + b * b) / 12
        return (side, side, m * a * a / 2)
    moment = 2 * m * a * a / 5
    return (moment, moment, moment)


def apply_min_friction(spec: Any, robots: list[BuiltRobot]) -> None:
    """Gazebo's friction rule, pair mu = min(mu_a, mu_b) (ODEPhysics.cc ``Collide``).

    MuJoCo takes the element-wise maximum unless one geom has a higher ``priority``, whose
    parameters then win; giving lower friction a higher priority makes the pair use the minimum.
    """
    mus: dict[str, float] = {}
    for geom in spec.geoms:
        if geom.contype or geom.conaffinity:
            mus[geom.name] = float(geom.friction[0])
    ranks = {mu: rank for rank, mu in enumerate(sorted(set(mus.values()), reverse=True))}
    for geom in spec.geoms:
        if geom.name in mus:
            geom.priority = ranks[mus[geom.name]]
