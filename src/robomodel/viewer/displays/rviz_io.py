"""Displays in ``.rviz`` files: option values read from a display's settings and written back.

An option's name is its key in RViz 2's config; ``/`` in a name is a nested property
(``Shape/Color`` is ``Shape: {Color: ...}``); a display's ``ros1_keys`` names the ROS 1 key
where RViz 1 calls it otherwise (Marker's ``Marker Topic``). ``Topic`` is RViz 2's map
(``Value``, ``Depth`` = Queue Size, the QoS policies: rviz_common ``RosTopicDisplay``) and a
flat key in ROS 1 with ``Queue Size`` beside it. Values RViz would not take are skipped and
named (the option keeps its default), as RViz's properties keep theirs.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.viewer.displays.base import Display, OptionKind
from robomodel.viewer.rviz_model import RvizDialect, RvizDisplay, freeze, thaw

__all__ = ["display_entry", "display_values"]

# RViz 2's defaults for a topic's QoS (rviz_common/ros_topic_display.hpp, qos_profile_property)
_TOPIC_QOS = {
    "Durability Policy": "Volatile",
    "History Policy": "Keep Last",
    "Reliability Policy": "Reliable",
}


def _key(cls: type[Display], name: str, dialect: RvizDialect) -> tuple[str, ...]:
    key = cls.ros1_keys.get(name, name) if dialect is RvizDialect.ROS1 else name
    return tuple(key.split("/"))


def _in(cls: type[Display], name: str, dialect: RvizDialect) -> bool:
    """Whether the option is in ``dialect``'s configs (RViz 1 has no QoS policies)."""
    return dialect is RvizDialect.ROS2 or name not in cls.ros2_only


def _get(settings: Mapping[str, Any], path: tuple[str, ...]) -> Any:
    node: Any = settings
    for part in path:
        if not isinstance(node, Mapping) or part not in node:
            return None
        node = node[part]
    return node


def _put(tree: dict[str, Any], path: tuple[str, ...], value: Any) -> None:
    for part in path[:-1]:
        child = tree.get(part)
        if not isinstance(child, dict):
            child = tree[part] = {} if not isinstance(child, Mapping) else dict(child)
        tree = child
    tree[path[-1]] = value


def display_values(
    cls: type[Display], settings: Mapping[str, Any], dialect: RvizDialect
) -> tuple[dict[str, Any], list[str]]:
    """Option values found in ``settings`` (a config display's), and one line per value
    skipped."""
    values: dict[str, Any] = {}
    skipped: list[str] = []
    for option in cls.options:
        if not _in(cls, option.name, dialect):
            continue
        raw = _get(settings, _key(cls, option.name, dialect))
        if option.kind is OptionKind.TOPIC and isinstance(raw, Mapping):
            has_queue = any(o.name == "Queue Size" for o in cls.options)
            if has_queue and "Queue Size" not in values and raw.get("Depth") is not None:
                values["Queue Size"] = raw["Depth"]
            raw = raw.get("Value")
        if option.name == "Queue Size" and raw is None:
            continue  # from the Topic map (ROS 2) or the default
        if raw is None:
            continue
        try:
            values[option.name] = option.coerce(thaw(raw) if option.kind is OptionKind.MAP else raw)  # fmt: skip
        except RobomodelError as exc:
            skipped.append(str(exc))
    if "Queue Size" in values:
        try:
            values["Queue Size"] = cls.option_spec("Queue Size").coerce(values["Queue Size"])
        except RobomodelError as exc:
            del values["Queue Size"]
            skipped.append(str(exc))
    return values, skipped


def _implied(cls: type[Display], settings: Mapping[str, Any], dialect: RvizDialect) -> dict[str, Any]:  # fmt: skip
    values = {o.name: o.coerce(o.default) for o in cls.options}
    values.update(display_values(cls, settings, dialect)[0])
    return values


def display_entry(
    display: Display, dialect: RvizDialect, base: RvizDisplay | None = None
) -> RvizDisplay:
    """The config entry of ``display``: ``base`` (the one it was read from) with what
    changed, or, for a new display, every option (as RViz writes all its properties)."""
    cls = type(display)
    prefix = "rviz" if dialect is RvizDialect.ROS1 else "rviz_default_plugins"
    kind = (
        (cls.ros1_class_name or cls.class_name) if dialect is RvizDialect.ROS1 else cls.class_name
    )
    class_name = base.class_name if base is not None else f"{prefix}/{kind}"
    tree: dict[str, Any] = thaw(base.settings) if base is not None else {}
    before = _implied(cls, base.settings, dialect) if base is not None else None
    for option in cls.options:
        value = display.values[option.name]
        if not _in(cls, option.name, dialect):
            continue
        if before is not None and before[option.name] == value:
            continue
        _write(tree, cls, option.name, value, dialect, display)
    return RvizDisplay(class_name, display.name, display.enabled, MappingProxyType(freeze(tree)))


def _write(tree: dict[str, Any], cls: type[Display], name: str, value: Any, dialect: RvizDialect, display: Display) -> None:  # fmt: skip
    option = cls.option_spec(name)
    out = thaw(value) if option.kind is OptionKind.MAP else value
    if dialect is RvizDialect.ROS2 and option.kind is OptionKind.TOPIC:
        topic = tree.get(name)
        topic = dict(topic) if isinstance(topic, Mapping) else dict(_TOPIC_QOS)
        topic["Value"] = value
        if "Queue Size" in display.values:
            topic["Depth"] = display.values["Queue Size"]
        tree[name] = topic
        return
    if dialect is RvizDialect.ROS2 and name == "Queue Size" and any(o.kind is OptionKind.TOPIC for o in cls.options):  # fmt: skip
        topic = tree.get("Topic")
        if isinstance(topic, Mapping):
            tree["Topic"] = {**topic, "Depth": value}
        return
    _put(tree, _key(cls, name, dialect), out)
