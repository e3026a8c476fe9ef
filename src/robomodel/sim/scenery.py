"""A world's shapes as the viewer's scenery (what Gazebo's client draws besides the robots)."""

from __future__ import annotations

from typing import Any

__all__ = ["scenery_of"]


def scenery_of(world: Any) -> tuple[Any, ...]:
    """The world's boxes, cylinders and spheres as the viewer's scenery.

    Static shapes are posed in ``world``; moving ones (mass > 0) in the TF frame the simulator
    publishes for them. Planes are left out: the viewer's grid is the ground.
    """
    from robomodel.sim.build.scene import shape_body_name
    from robomodel.sim.world import ShapeKind
    from robomodel.viewer.scenery import SceneryShape

    shapes = []
    for i, shape in enumerate(world.shapes):
        if shape.kind is ShapeKind.PLANE:
            continue
        name = shape_body_name(shape, i)
        moving = shape.mass_kg > 0
        x, y, z, roll, pitch, yaw = shape.pose
        shapes.append(
            SceneryShape(
                name=name,
                frame=name if moving else "world",
                kind=shape.kind.value,
                size_m=shape.size,
                xyz_m=(0.0, 0.0, 0.0) if moving else (x, y, z),
                rpy_rad=(0.0, 0.0, 0.0) if moving else (roll, pitch, yaw),
                rgba=shape.rgba,
            )
        )
    return tuple(shapes)
