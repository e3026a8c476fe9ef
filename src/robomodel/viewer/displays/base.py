"""The display plug-in family: RViz's displays (Marker, LaserScan, PointCloud2, ...) in the page.

The contract, for anyone writing a display type:

- A display is a subclass of :class:`Display` decorated with :func:`register_display`. Its
  ``class_name`` is RViz's class without the plugin prefix (``"Marker"``: ``rviz/Marker`` in
  ROS 1, ``rviz_default_plugins/Marker`` in ROS 2), ``message_types`` the ROS 2 type names its
  ``Topic`` takes (the first is used when the graph does not tell), ``options`` its property
  table with RViz's names and defaults (``Topic``, ``Queue Size``, ``Size (m)``, ...). Option
  values live in ``self.values`` (name -> value) and are read with :meth:`Display.option`.
- Threading: every method is called on the viewer's loop thread (the one that owns the nodes,
  see :mod:`robomodel.viewer.tools.base`), so a display needs no locks. GUI callbacks post.
- Messages: the :class:`~robomodel.viewer.displays.manager.DisplayManager` subscribes the
  viewer's node to what :meth:`Display.subscriptions` returns (by default one subscription to
  the ``Topic`` option with ``Queue Size`` as depth) and re-subscribes when that changes. The
  callback is :meth:`Display.receive`, which counts the message and calls :meth:`on_message`.
  Message classes come from :func:`robomodel.runtime.msg.get_message_type` (built from the
  type's definition); never write one by hand.
- Drawing: :meth:`Display.draw` is called about 10 times a second with a
  :data:`FrameLookup`; it places its data through TF in the fixed frame (with the message's
  stamp where the frame moves) and returns a :class:`DisplayStatus`, shown in the Displays
  panel (a frame without a transform gives RViz's "No transform from [x] to [y]").
- Scene nodes go below :attr:`Display.root` (``/displays/<display name>``), best through
  :meth:`Display.add_node` so that disabling, renaming and closing remove them.
- Enable/disable (:meth:`set_enabled`), option changes (:meth:`set_option`, which calls
  :meth:`on_option_changed`), reset (:meth:`reset`) and :meth:`close` are handled by the base;
  override the ``on_*`` hooks for more.
- A display that needs page controls (an image) overrides :meth:`build_panel`.
"""

from __future__ import annotations

import importlib
import pkgutil
import re
from collections.abc import Callable, Mapping
from pathlib import Path
from types import MappingProxyType
from typing import Any, ClassVar, TypeVar

from robomodel.errors import RobomodelError
from robomodel.runtime.qos import Durability, QoSProfile
from robomodel.viewer.displays.context import (
    DisplayContext,
    DisplayStatus,
    FrameLookup,
    Placement,
    StatusLevel,
    SubscriptionSpec,
    stamp_ns,
)
from robomodel.viewer.displays.options import DisplayOptionError, Option, OptionKind, color_rgb
from robomodel.viewer.displays.topic_qos import QOS_OPTION_NAMES, qos_options, topic_qos

__all__ = [
    "Display",
    "DisplayContext",
    "DisplayOptionError",
    "DisplayStatus",
    "FrameLookup",
    "Option",
    "OptionKind",
    "Placement",
    "StatusLevel",
    "SubscriptionSpec",
    "UnknownDisplayError",
    "color_rgb",
    "display_class",
    "display_classes",
    "is_rviz_display",
    "load_builtin_displays",
    "register_display",
    "stamp_ns",
]


class UnknownDisplayError(RobomodelError):
    """A display class robomodel does not have (the message lists those it has)."""


_SAFE = re.compile(r"[^A-Za-z0-9_.\-]")


class Display:
    """An RViz display in the page (see the module docstring for the contract).

    Args:
        name: The display's name in the panel (RViz's ``Name``).
        context: The viewer's parts a display uses.
        values: Option values (missing ones get their defaults).
        enabled: Whether it starts enabled.
    """

    class_name: ClassVar[str] = ""
    message_types: ClassVar[tuple[str, ...]] = ()
    options: ClassVar[tuple[Option, ...]] = ()
    ros1_keys: ClassVar[Mapping[str, str]] = MappingProxyType({})
    """Option name -> ROS 1 config key where RViz 1 names it otherwise (``Marker Topic``)."""
    ros1_class_name: ClassVar[str] = ""
    """RViz 1's class where it differs (Wrench is ``rviz/WrenchStamped`` in ROS 1)."""
    ros2_only: ClassVar[frozenset[str]] = frozenset()
    """Options RViz 1 does not have: not read from or written to ROS 1 configs."""
    topic_qos_defaults: ClassVar[Mapping[str, str]] = MappingProxyType({})
    """RViz 2 policies (``"Durability Policy": "Transient Local"``) other than rclcpp's default
    for this display's ``Topic``."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        """A display with a ``Topic`` gets RViz 2's QoS policies below it (every
        ``RosTopicDisplay`` has them), unless it declares them itself."""
        super().__init_subclass__(**kwargs)
        names = {o.name for o in cls.options}
        if any(o.name == "Topic" and o.kind is OptionKind.TOPIC for o in cls.options):
            if not names & set(QOS_OPTION_NAMES):
                cls.options = (*cls.options, *qos_options(cls.topic_qos_defaults))
            cls.ros2_only = cls.ros2_only | set(QOS_OPTION_NAMES)

    def __init__(
        self,
        name: str,
        context: DisplayContext,
        values: Mapping[str, Any] | None = None,
        *,
        enabled: bool = True,
    ) -> None:
        self.name = name
        self.context = context
        self.enabled = enabled
        self.values: dict[str, Any] = {o.name: o.coerce(o.default) for o in self.options}
        for key, value in (values or {}).items():
            if key in self.values:
                self.values[key] = self.option_spec(key).coerce(value)
        self.messages_received = 0
        self.option_listeners: list[Callable[[Display], object]] = []
        self.status = DisplayStatus.ok()
        self.config_entry: Any = None  # the .rviz entry it was read from (None: added here)
        self._nodes: dict[str, Any] = {}

    # -- options -------------------------------------------------------------------------------
    @classmethod
    def option_spec(cls, name: str) -> Option:
        for option in cls.options:
            if option.name == name:
                return option
        known = ", ".join(o.name for o in cls.options) or "none"
        raise DisplayOptionError(f"{cls.class_name} has no option '{name}'; options: {known}")

    def option(self, name: str) -> Any:
        return self.values[name]

    def map_entries(self, name: str) -> Mapping[str, Any]:
        """The entries of a MAP option the panel shows as checkboxes (default: its value; TF
        adds every frame seen, which its option holds only once switched)."""
        entries: Mapping[str, Any] = self.values[name]
        return entries

    def set_option(self, name: str, value: Any) -> None:
        """Set an option (loop thread). Raises :class:`DisplayOptionError` for a bad value."""
        new = self.option_spec(name).coerce(value)
        if new == self.values[name]:
            return
        self.values[name] = new
        self.on_option_changed(name)
        for listener in self.option_listeners:  # the manager: re-subscribe now, not at its tick
            listener(self)

    def on_option_changed(self, name: str) -> None:
        """Hook: an option changed (the manager re-subscribes on its own). Default: redraw."""
        self.reset()

    # -- messages ------------------------------------------------------------------------------
    @property
    def topic(self) -> str:
        return str(self.values.get("Topic", ""))

    def subscriptions(self) -> tuple[SubscriptionSpec, ...]:
        """What to subscribe to now; default: ``Topic`` with :meth:`topic_qos`, typed as the
        graph shows it when that type is one of ``message_types``."""
        if not self.enabled or not self.message_types or not self.topic:
            return ()
        known = self.context.topic_types(self.topic)
        type_name = next((t for t in self.message_types if t in known), self.message_types[0])
        qos = self.topic_qos()
        latched = qos.durability is Durability.TRANSIENT_LOCAL
        return (SubscriptionSpec(self.topic, type_name, self.receive, qos.depth, latched, qos=qos),)

    def topic_qos(self) -> QoSProfile:
        """The ``Topic`` subscription's QoS: ``Queue Size`` as depth and the policies."""
        depth = max(1, int(self.values.get("Queue Size", 10)))
        return topic_qos(self.values, depth)

    def receive(self, msg: Any) -> None:
        self.messages_received += 1
        self.on_message(msg)

    def on_message(self, msg: Any) -> None:
        """Hook: a message arrived (loop thread). Keep it cheap; draw in :meth:`draw`."""

    def topic_status(self) -> DisplayStatus | None:
        """RViz's Topic status: a warning until the first message (None: not subscribed)."""
        if not self.message_types or not self.enabled:
            return None
        if not self.topic:
            return DisplayStatus.error("Error subscribing: Empty topic name")
        if self.messages_received == 0:
            return DisplayStatus.warn("No messages received")
        return None

    # -- drawing -------------------------------------------------------------------------------
    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        """Bring the scene up to date (loop thread, ~10 Hz); the display's status."""
        return self.topic_status() or DisplayStatus.ok()

    @property
    def root(self) -> str:
        """The scene path all of this display's nodes go below."""
        return f"/displays/{_SAFE.sub('_', self.name) or '_'}"

    def add_node(self, key: str, kind: str, **kwargs: Any) -> Any:
        """``scene.add_<kind>(root/key, **kwargs)``, replacing an earlier node of that key."""
        self.remove_node(key)
        handle = getattr(self.context.scene, f"add_{kind}")(f"{self.root}/{key}", **kwargs)
        self._nodes[key] = handle
        return handle

    def node(self, key: str) -> Any:
        return self._nodes.get(key)

    def remove_node(self, key: str) -> None:
        handle = self._nodes.pop(key, None)
        if handle is not None:
            handle.remove()

    def remove_nodes(self) -> None:
        for key in list(self._nodes):
            self.remove_node(key)

    # -- lifecycle -----------------------------------------------------------------------------
    def set_enabled(self, enabled: bool) -> None:
        if enabled == self.enabled:
            return
        self.enabled = enabled
        if not enabled:
            self.reset()
        self.on_enabled_changed()

    def on_enabled_changed(self) -> None:
        """Hook: after :meth:`set_enabled`."""

    def rename(self, name: str) -> None:
        """A new name: the nodes move (they are drawn again below the new root)."""
        self.remove_nodes()
        self.name = name
        self.on_renamed()

    def on_renamed(self) -> None:
        """Hook: after :meth:`rename` (drop anything keyed on the old scene paths)."""

    def reset(self) -> None:
        """RViz's Reset: forget what was drawn (the scene nodes go)."""
        self.remove_nodes()

    def on_time_jump(self) -> None:
        """ROS time went back: start over (RViz resets every display)."""
        self.reset()

    def build_panel(self, gui: Any) -> None:
        """Hook: add page controls inside the display's folder."""

    def build_dock(self, gui: Any) -> None:
        """Hook: add a panel of the display's own, outside the Displays tree (an image, as
        RViz docks the Image display's panel beside the 3D view)."""

    def close(self) -> None:
        self.remove_nodes()


_REGISTRY: dict[str, type[Display]] = {}
# RViz's own display plugins (ROS 1, ROS 2); another package's "Marker" is not RViz's
_RVIZ_PACKAGES = ("", "rviz", "rviz_default_plugins")
D = TypeVar("D", bound=type[Display])


def register_display(cls: D) -> D:
    """Class decorator: make ``cls`` addable by its ``class_name``."""
    if not cls.class_name:
        raise TypeError(f"{cls.__name__} has no class_name")
    _REGISTRY[cls.class_name] = cls
    return cls


_LOADED: list[bool] = []
_NOT_DISPLAYS = ("attach", "base", "manager", "options", "panel", "rviz_io")


def load_builtin_displays() -> None:
    """Import every display module of this package once (each registers its classes)."""
    if _LOADED:
        return
    _LOADED.append(True)
    package = __name__.rpartition(".")[0]
    for info in pkgutil.iter_modules([str(Path(__file__).parent)]):
        if not info.name.startswith("_") and info.name not in _NOT_DISPLAYS:
            importlib.import_module(f"{package}.{info.name}")


def display_classes() -> Mapping[str, type[Display]]:
    """Every registered display class by ``class_name`` (the package's modules loaded)."""
    load_builtin_displays()
    return MappingProxyType(dict(sorted(_REGISTRY.items())))


def is_rviz_display(class_name: str, kinds: tuple[str, ...] | None = None) -> bool:
    """Whether ``class_name`` is RViz's own display of one of ``kinds`` (None: any robomodel
    has)."""
    package, _, kind = class_name.rpartition("/")
    known = display_classes() if kinds is None else kinds
    return package in _RVIZ_PACKAGES and _ros1_kind(package, kind) in known


def _ros1_kind(package: str, kind: str) -> str:
    """robomodel's class name for RViz 1's ``rviz/<kind>`` (``WrenchStamped`` -> ``Wrench``)."""
    if package == "rviz":
        for cls in display_classes().values():
            if cls.ros1_class_name == kind:
                return cls.class_name
    return kind


def display_class(class_name: str) -> type[Display]:
    """The display for ``Marker``, ``rviz/Marker`` or ``rviz_default_plugins/Marker``.

    Raises:
        UnknownDisplayError: robomodel has no such display.
    """
    classes = display_classes()
    package, _, kind = class_name.rpartition("/")
    kind = _ros1_kind(package, kind)
    if kind not in classes or package not in _RVIZ_PACKAGES:
        raise UnknownDisplayError(
            f"robomodel has no display '{class_name}'; it has: {', '.join(classes)}"
        )
    return classes[kind]
