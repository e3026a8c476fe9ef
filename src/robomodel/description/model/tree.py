"""The derived tree view of a robot, built exactly as urdfdom's ``initTree``/``initRoot``.

urdfdom iterates joints in ``std::map`` order, i.e. sorted bytewise by joint name, so children
lists are ordered by joint *name*, not file order; this is what check_urdf, urdf_to_graphviz and
pinocchio show. A link with two parent joints keeps the last one (in name order) as its parent
but is listed under both parents, as urdfdom does.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robomodel.description.model.joint import Joint
from robomodel.errors import RobomodelError

if TYPE_CHECKING:
    from robomodel.description.model.robot import Robot

__all__ = ["KinematicTree", "TreeError", "build_tree", "sorted_bytewise"]


class TreeError(RobomodelError):
    """The joints do not form a tree with exactly one root (urdfdom's fatal tree errors)."""

    def __init__(self, message: str, joint: str | None = None) -> None:
        super().__init__(message)
        self.joint = joint


def sorted_bytewise(names: list[str]) -> list[str]:
    """Sort like ``std::map<std::string, ...>`` (UTF-8 bytes; equal to code-point order)."""
    return sorted(names)


@dataclass(frozen=True, slots=True)
class KinematicTree:
    """Root, parent and child maps. Children are ``(joint, child_link)`` pairs in name order."""

    root: str
    parent_joint: Mapping[str, Joint]
    child_joints: Mapping[str, tuple[Joint, ...]]

    def parent(self, link: str) -> str | None:
        """The parent link of ``link`` (None for the root)."""
        joint = self.parent_joint.get(link)
        return None if joint is None else joint.parent

    def children(self, link: str) -> tuple[str, ...]:
        """Child links of ``link`` in urdfdom's order."""
        return tuple(j.child for j in self.child_joints.get(link, ()))

    def walk(self) -> Iterator[tuple[int, Joint]]:
        """Depth-first ``(depth, joint)`` pairs from the root, never entering a link twice."""
        seen = {self.root}
        stack: list[tuple[int, Joint]] = [
            (1, j) for j in reversed(self.child_joints.get(self.root, ()))
        ]
        while stack:
            depth, joint = stack.pop()
            yield depth, joint
            if joint.child in seen:
                continue
            seen.add(joint.child)
            stack.extend((depth + 1, j) for j in reversed(self.child_joints.get(joint.child, ())))

    def links_depth_first(self) -> tuple[str, ...]:
        """Links reachable from the root, each once, in depth-first order."""
        order = [self.root]
        seen = {self.root}
        for _, joint in self.walk():
            if joint.child not in seen:
                seen.add(joint.child)
                order.append(joint.child)
        return tuple(order)


def build_tree(robot: Robot) -> KinematicTree:
    """Build the tree of ``robot`` or raise :class:`TreeError` with urdfdom's message."""
    link_names = {link.name for link in robot.links}
    by_name: dict[str, Joint] = {}
    for joint in robot.joints:
        by_name.setdefault(joint.name, joint)
    parent_joint: dict[str, Joint] = {}
    child_joints: dict[str, list[Joint]] = {}
    for name in sorted_bytewise(list(by_name)):
        joint = by_name[name]
        if not joint.parent or not joint.child:
            raise TreeError(
                f"Failed to build tree: Joint [{name}] is missing a parent and/or child link "
                "specification.",
                name,
            )
        if joint.child not in link_names:
            raise TreeError(
                f"Failed to build tree: child link [{joint.child}] of joint [{name}] not found",
                name,
            )
        if joint.parent not in link_names:
            raise TreeError(
                f"Failed to build tree: parent link [{joint.parent}] of joint [{name}] not "
                "found.  This is not valid according to the URDF spec. Every link you refer to "
                "from a joint needs to be explicitly defined in the robot description. To fix "
                f"this problem you can either remove this joint [{name}] from your urdf file, "
                f'or add "<link name="{joint.parent}" />" to your urdf file.',
                name,
            )
        parent_joint[joint.child] = joint
        child_joints.setdefault(joint.parent, []).append(joint)
    roots = [name for name in sorted_bytewise(list(link_names)) if name not in parent_joint]
    if len(roots) > 1:
        raise TreeError(
            f"Failed to find root link: Two root links found: [{roots[0]}] and [{roots[1]}]"
        )
    if not roots:
        raise TreeError(
            "Failed to find root link: No root link found. The robot xml is not a valid tree."
        )
    return KinematicTree(
        root=roots[0],
        parent_joint=parent_joint,
        child_joints={k: tuple(v) for k, v in child_joints.items()},
    )
