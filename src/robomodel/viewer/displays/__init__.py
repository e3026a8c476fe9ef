"""RViz's displays in the page: the :class:`Display` plug-in family and its registry.

Every module of this package is imported by :func:`load_builtin_displays`, so a new display
type is one new module with a :func:`register_display` class (no list to edit).
"""

from __future__ import annotations

from robomodel.viewer.displays.base import (
    Display,
    DisplayContext,
    DisplayOptionError,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    Placement,
    StatusLevel,
    SubscriptionSpec,
    UnknownDisplayError,
    display_class,
    display_classes,
    is_rviz_display,
    load_builtin_displays,
    register_display,
    stamp_ns,
)

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
    "display_class",
    "display_classes",
    "is_rviz_display",
    "load_builtin_displays",
    "register_display",
    "stamp_ns",
]
