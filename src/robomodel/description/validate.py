"""Checks beyond urdfdom: problems it accepts silently but that break kinematics or physics.

Each check returns warnings with the location of the offending element; ``robomodel check
--strict`` turns them into errors. None of them can hang: cycles are found by colouring.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator
from dataclasses import dataclass

from robomodel.description.model import (
    Box,
    Capsule,
    Collision,
    Cylinder,
    Inertia,
    JointType,
    Mesh,
    Robot,
    SourceSpan,
    Sphere,
    Visual,
)
from robomodel.description.packages import PackageIndex
from robomodel.errors import (
    Diagnostic,
    PackageNotFoundError,
    RobomodelError,
    Severity,
    SourceLocation,
)

__all__ = ["principal_moments", "validate", "validate_resources"]

_AXIS_TYPES = (JointType.REVOLUTE, JointType.CONTINUOUS, JointType.PRISMATIC, JointType.PLANAR)


def _warn(robot: Robot, span: SourceSpan | None, message: str, code: str) -> Diagnostic:
    location = span.location if span is not None else SourceLocation(robot.source_path)
    return Diagnostic(Severity.WARNING, message, location, code)


def principal_moments(inertia: Inertia) -> tuple[float, float, float]:
    """Eigenvalues of the symmetric inertia tensor, ascending (closed form, no numpy)."""
    a, b, c = inertia.ixx, inertia.iyy, inertia.izz
    d, e, f = inertia.ixy, inertia.iyz, inertia.ixz
    p1 = d * d + e * e + f * f
    if p1 == 0.0:
        low, mid, high = sorted((a, b, c))
        return (low, mid, high)
    q = (a + b + c) / 3.0
    p2 = (a - q) ** 2 + (b - q) ** 2 + (c - q) ** 2 + 2.0 * p1
    p = math.sqrt(p2 / 6.0)
    # det((A - qI) / p) / 2
    ba, bb, bc = (a - q) / p, (b - q) / p, (c - q) / p
    bd, be, bf = d / p, e / p, f / p
    r = (ba * (bb * bc - be * be) - bd * (bd * bc - be * bf) + bf * (bd * be - bb * bf)) / 2.0
    phi = math.pi / 3.0 if r <= -1 else 0.0 if r >= 1 else math.acos(r) / 3.0
    high = q + 2.0 * p * math.cos(phi)
    low = q + 2.0 * p * math.cos(phi + 2.0 * math.pi / 3.0)
    return (low, 3.0 * q - high - low, high)


def _inertial_checks(robot: Robot) -> Iterator[Diagnostic]:
    for link in robot.links:
        inertial = link.inertial
        if inertial is None:
            continue
        where = f"link '{link.name}'"
        if inertial.mass_kg <= 0.0:
            yield _warn(
                robot,
                inertial.span,
                f"{where} has mass {inertial.mass_kg:g} kg; a link with <inertial> needs a "
                "positive mass (remove <inertial> for a massless frame)",
                "mass",
            )
            continue  # one warning per inertial: a massless inertia is not checked further
        moments = principal_moments(inertial.inertia)
        tol = 1e-12 * max(1.0, max(abs(m) for m in moments))
        if moments[0] <= 0.0:
            yield _warn(
                robot,
                inertial.span,
                f"{where}: inertia is not positive definite (principal moments "
                f"{moments[0]:.6g}, {moments[1]:.6g}, {moments[2]:.6g} kg·m²); every principal "
                "moment must be > 0",
                "inertia",
            )
        elif moments[0] + moments[1] < moments[2] - tol:
            yield _warn(
                robot,
                inertial.span,
                f"{where}: inertia violates the triangle inequality (principal moments "
                f"{moments[0]:.6g} + {moments[1]:.6g} < {moments[2]:.6g} kg·m²); no rigid body "
                "has this inertia",
                "inertia",
            )


def _joint_checks(robot: Robot) -> Iterator[Diagnostic]:
    for joint in robot.joints:
        if joint.type in _AXIS_TYPES:
            norm = math.sqrt(sum(c * c for c in joint.axis))
            if norm == 0.0:
                yield _warn(
                    robot,
                    joint.span,
                    f"joint '{joint.name}' has a zero axis; give a unit vector such as "
                    '<axis xyz="0 0 1"/>',
                    "axis",
                )
            elif abs(norm - 1.0) > 1e-6:
                yield _warn(
                    robot,
                    joint.span,
                    f"joint '{joint.name}' axis {joint.axis} has length {norm:.6g}, not 1; "
                    "rotations use its direction but prismatic travel differs between tools",
                    "axis",
                )
        limit = joint.limit
        if (
            limit is not None
            and limit.lower is not None
            and limit.upper is not None
            and limit.lower > limit.upper
            and joint.type in (JointType.REVOLUTE, JointType.PRISMATIC)
        ):
            yield _warn(
                robot,
                joint.span,
                f"joint '{joint.name}' has lower limit {limit.lower:g} > upper limit "
                f"{limit.upper:g}; no position is allowed",
                "limits",
            )
        if joint.parent == joint.child and joint.parent:
            yield _warn(
                robot,
                joint.span,
                f"joint '{joint.name}' connects link '{joint.child}' to itself (a self-loop; "
                "check_urdf recurses forever on it)",
                "self-loop",
            )


def _mimic_checks(robot: Robot) -> Iterator[Diagnostic]:
    names = set(robot.joint_names)
    target = {j.name: j.mimic.joint for j in robot.joints if j.mimic is not None}
    for joint in robot.joints:
        if joint.mimic is None:
            continue
        if joint.mimic.joint not in names:
            yield _warn(
                robot,
                joint.span,
                f"joint '{joint.name}' mimics unknown joint '{joint.mimic.joint}'",
                "mimic",
            )
            continue
        seen = [joint.name]
        current = joint.mimic.joint
        while current in target and current not in seen:
            seen.append(current)
            current = target[current]
        if current == joint.name:
            yield _warn(
                robot,
                joint.span,
                f"mimic cycle: {' -> '.join([*seen, current])}; a mimic chain must end at an "
                "independent joint",
                "mimic-cycle",
            )


def _structure_checks(robot: Robot) -> Iterator[Diagnostic]:
    tree = robot.tree()
    parents: dict[str, list[str]] = {}
    for joint in robot.joints:
        parents.setdefault(joint.child, []).append(joint.name)
    for child, joints in parents.items():
        if len(joints) > 1:
            yield _warn(
                robot,
                robot.link(child).span,
                f"link '{child}' has {len(joints)} parent joints ({', '.join(sorted(joints))}); "
                "a URDF must be a tree (urdfdom keeps the last in name order)",
                "two-parents",
            )
    reachable = set(tree.links_depth_first())
    for link in robot.links:
        if link.name not in reachable:
            yield _warn(
                robot,
                link.span,
                f"link '{link.name}' is not connected to the root '{tree.root}' (it is part of "
                "a kinematic cycle); urdfdom silently leaves it out of the tree",
                "cycle",
            )


def _geometry_checks(robot: Robot) -> Iterator[Diagnostic]:
    for link in robot.links:
        elements: tuple[Visual | Collision, ...] = (*link.visuals, *link.collisions)
        for element in elements:
            g = element.geometry
            dims: tuple[float, ...]
            if isinstance(g, Box):
                dims = g.size_m
            elif isinstance(g, (Cylinder, Capsule)):
                dims = (g.radius_m, g.length_m)
            elif isinstance(g, Sphere):
                dims = (g.radius_m,)
            else:
                continue
            if min(dims) <= 0.0:
                yield _warn(
                    robot,
                    element.span,
                    f"link '{link.name}': {type(g).__name__.lower()} has a non-positive "
                    f"dimension {dims}",
                    "geometry",
                )


def validate(robot: Robot) -> list[Diagnostic]:
    """Return robomodel's extra warnings for a parsed robot (see the module docstring)."""
    found: list[Diagnostic] = []
    for check in (
        _inertial_checks,
        _joint_checks,
        _mimic_checks,
        _structure_checks,
        _geometry_checks,
    ):
        found.extend(check(robot))
    return found


@dataclass(frozen=True, slots=True)
class _MeshUse:
    """One ``<mesh>`` of a link's visual or collision, with where it is written."""

    link: str
    filename: str
    span: SourceSpan | None


def _mesh_uses(robot: Robot) -> Iterator[_MeshUse]:
    """Every mesh of the robot, link by link, visuals before collisions."""
    for link in robot.links:
        elements: tuple[Visual | Collision, ...] = (*link.visuals, *link.collisions)
        for element in elements:
            if isinstance(element.geometry, Mesh):
                yield _MeshUse(link.name, element.geometry.filename, element.span)


def _more_uses_of_unknown_packages(
    robot: Robot, spans_by_package: dict[str, list[SourceSpan | None]]
) -> Iterator[Diagnostic]:
    """One warning per unknown package used more than once, at its second use (the first
    use has its own warning): a missing package is one problem, not one per mesh."""
    for name, spans in spans_by_package.items():
        if len(spans) > 1:
            yield _warn(
                robot,
                spans[1],
                f"{len(spans) - 1} more meshes use the unknown package '{name}'",
                "mesh",
            )


def validate_resources(
    robot: Robot, packages: PackageIndex, base_dir: str | os.PathLike[str] | None
) -> list[Diagnostic]:
    """Warn about mesh files that do not exist and ``package://`` URIs that do not resolve.

    An unknown package is reported once, at its first mention, with how many meshes use it.
    """
    found: list[Diagnostic] = []
    missing_packages: dict[str, list[SourceSpan | None]] = {}
    missing_file: dict[str, bool] = {}  # by filename: each file is looked for once
    for use in _mesh_uses(robot):
        where = f"link '{use.link}': mesh"
        try:
            path = packages.resolve(use.filename, base_dir=base_dir)
        except PackageNotFoundError as exc:
            spans = missing_packages.setdefault(exc.name, [])
            spans.append(use.span)
            if len(spans) == 1:
                message = f"{where} '{use.filename}' does not resolve: {exc}"
                found.append(_warn(robot, use.span, message, "mesh"))
            continue
        except RobomodelError as exc:
            found.append(_warn(robot, use.span, f"{where} '{use.filename}': {exc}", "mesh"))
            continue
        if use.filename not in missing_file:
            missing_file[use.filename] = not path.is_file()
        if missing_file[use.filename]:
            message = f"{where} file '{use.filename}' does not exist ({path})"
            found.append(_warn(robot, use.span, message, "mesh"))
    found.extend(_more_uses_of_unknown_packages(robot, missing_packages))
    return found
