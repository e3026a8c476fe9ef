"""The robot: the root of the URDF model."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from robomodel.description.model.extensions import GazeboBlock, Ros2Control, Transmission
from robomodel.description.model.geometry import Material
from robomodel.description.model.joint import Joint
from robomodel.description.model.link import Link
from robomodel.description.model.raw import RawElement
from robomodel.errors import RobomodelError, describe_unknown

if TYPE_CHECKING:
    from robomodel.description.model.tree import KinematicTree

__all__ = ["Robot", "UnknownNameError"]


class UnknownNameError(RobomodelError, KeyError):
    """A link, joint or material name that the robot does not have."""

    def __init__(self, kind: str, name: str, available: tuple[str, ...]) -> None:
        self.kind = kind
        self.name = name
        self.available = available
        super().__init__(describe_unknown(f"unknown {kind}", name, available, f"{kind}s are"))

    def __str__(self) -> str:
        return str(self.args[0])


@dataclass(frozen=True, slots=True)
class Robot:
    """A whole URDF robot description. Plain, immutable data.

    ``links`` and ``joints`` keep file order. ``version`` is the ``version`` attribute as
    written (``None`` when absent, meaning 1.0). ``source_path`` is informative only.

    Equality is that of the robot, not of the document: links, joints, materials and
    transmissions are compared as collections whatever their order (yourdfpy's
    ``test_equality_different_link_order``; a URDF's meaning does not depend on it), while
    ``<gazebo>``, ``<ros2_control>`` and unknown top-level elements keep their order (a later
    ``<gazebo>`` block can override an earlier one). The writer still writes file order.
    """

    name: str
    links: tuple[Link, ...] = ()
    joints: tuple[Joint, ...] = ()
    materials: tuple[Material, ...] = ()
    transmissions: tuple[Transmission, ...] = ()
    gazebo: tuple[GazeboBlock, ...] = ()
    ros2_control: tuple[Ros2Control, ...] = ()
    extra: tuple[RawElement, ...] = ()
    version: str | None = None
    attributes: tuple[tuple[str, str], ...] = ()
    source_path: str | None = field(default=None, compare=False)
    _cache: dict[str, Any] = field(default_factory=dict, init=False, compare=False, repr=False)

    def _unordered_key(self) -> tuple[Any, ...]:
        def bag(items: tuple[Any, ...]) -> Counter[Any]:
            return Counter(items)

        return (
            self.name,
            bag(self.links),
            bag(self.joints),
            bag(self.materials),
            bag(self.transmissions),
            self.gazebo,
            self.ros2_control,
            self.extra,
            self.version,
            frozenset(self.attributes),
        )

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Robot):
            return NotImplemented
        return self._unordered_key() == other._unordered_key()

    def __hash__(self) -> int:
        return hash(
            (
                self.name,
                frozenset(self.link_names),
                frozenset(self.joint_names),
                len(self.links),
                len(self.joints),
            )
        )

    def _by_name(self, key: str, items: tuple[Any, ...]) -> dict[str, Any]:
        table = self._cache.get(key)
        if table is None:
            table = {}
            for item in items:
                table.setdefault(item.name, item)
            self._cache[key] = table
        return table

    @property
    def link_names(self) -> tuple[str, ...]:
        return tuple(link.name for link in self.links)

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(joint.name for joint in self.joints)

    def link(self, name: str) -> Link:
        """Return the link called ``name`` (``UnknownNameError`` lists the valid names)."""
        table: dict[str, Link] = self._by_name("links", self.links)
        try:
            return table[name]
        except KeyError:
            raise UnknownNameError("link", name, self.link_names) from None

    def joint(self, name: str) -> Joint:
        """Return the joint called ``name`` (``UnknownNameError`` lists the valid names)."""
        table: dict[str, Joint] = self._by_name("joints", self.joints)
        try:
            return table[name]
        except KeyError:
            raise UnknownNameError("joint", name, self.joint_names) from None

    def has_link(self, name: str) -> bool:
        return name in self._by_name("links", self.links)

    def has_joint(self, name: str) -> bool:
        return name in self._by_name("joints", self.joints)

    def material(self, name: str) -> Material:
        """Return the robot-level material called ``name``."""
        table: dict[str, Material] = self._by_name("materials", self.materials)
        try:
            return table[name]
        except KeyError:
            names = tuple(m.name for m in self.materials)
            raise UnknownNameError("material", name, names) from None

    def tree(self) -> KinematicTree:
        """The derived tree view (root, parents, children in urdfdom's order); cached."""
        tree = self._cache.get("tree")
        if tree is None:
            from robomodel.description.model.tree import build_tree

            tree = build_tree(self)
            self._cache["tree"] = tree
        return tree
