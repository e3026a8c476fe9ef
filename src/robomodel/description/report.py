"""Text and graph views that match urdfdom's ``check_urdf`` and ``urdf_to_graphviz``."""

from __future__ import annotations

from collections.abc import Iterator

from robomodel.description.model import Robot
from robomodel.description.model.pose import rpy_from_quat_xyzw

__all__ = ["check_urdf_text", "graphviz_text", "walk_children"]


def walk_children(robot: Robot) -> Iterator[tuple[int, int, str, str]]:
    """urdfdom's recursive child walk as ``(depth, index, parent, child)``, pre-order.

    A link is listed under every parent that names it (as urdfdom does for a link with two
    parents) but never entered while it is already on the current path, so self-loops and
    cycles reachable from the root terminate (check_urdf recurses forever on them).
    """
    tree = robot.tree()
    # Each frame: [link, next child index, depth, links on the path].
    stack: list[tuple[str, list[int], int, frozenset[str]]] = [
        (tree.root, [0], 1, frozenset({tree.root}))
    ]
    while stack:
        link, cursor, depth, path = stack[-1]
        children = tree.children(link)
        if cursor[0] >= len(children):
            stack.pop()
            continue
        index = cursor[0]
        cursor[0] += 1
        child = children[index]
        yield depth, index, link, child
        if child not in path:
            stack.append((child, [0], depth + 1, path | {child}))


def check_urdf_text(robot: Robot) -> str:
    """What ``check_urdf`` prints on stdout for a valid file, byte for byte."""
    tree = robot.tree()
    lines = [
        f"robot name is: {robot.name}",
        "---------- Successfully Parsed XML ---------------",
        f"root Link: {tree.root} has {len(tree.children(tree.root))} child(ren)",
    ]
    for depth, index, _, child in walk_children(robot):
        lines.append("    " * depth + f"child({index + 1}):  {child}")
    return "\n".join(lines) + "\n"


def _g(value: float) -> str:
    """C++ ``ostream << double`` with the default precision (6 significant digits)."""
    return f"{value:g}"


def graphviz_text(robot: Robot) -> str:
    """The ``.gv`` text ``urdf_to_graphviz`` writes, byte for byte."""
    tree = robot.tree()
    lines = ["digraph G {", "node [shape=box];", f'"{tree.root}" [label="{tree.root}"];']
    walk = list(walk_children(robot))
    lines.extend(f'"{child}" [label="{child}"];' for _, _, _, child in walk)
    lines.append("node [shape=ellipse, color=blue, fontcolor=blue];")
    for _, _, parent, child in walk:
        # urdfdom labels the edge with the child's parent_joint (the last in name order).
        joint = tree.parent_joint[child]
        x, y, z = joint.origin.xyz_m
        r, p, yaw = rpy_from_quat_xyzw(*joint.origin.quaternion_xyzw())
        lines.append(
            f'"{parent}" -> "{joint.name}" [label="xyz: {_g(x)} {_g(y)} {_g(z)} '
            f'\\nrpy: {_g(r)} {_g(p)} {_g(yaw)}"]'
        )
        lines.append(f'"{joint.name}" -> "{child}"')
    lines.append("}")
    return "\n".join(lines) + "\n"
