"""RViz's displays in the page: the :class:`Display` plug-in family and its registry.

Every module of this package is imported by :func:`load_builtin_displays`, so a new display
type is one new module with a :func:`register_display` class (no list to edit).
"""

from __future__ import annotations

import importlib
import pkgutil

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

_LOADED: list[bool] = []
_NOT_DISPLAYS = ("attach", "base", "manager", "options", "panel", "rviz_io")


def load_builtin_displays() -> None:
    """Import every display module of this package once (each registers its classes)."""
    if _LOADED:
        return
    _LOADED.append(True)
    for info in pkgutil.iter_modules(__path__):
        if not info.name.startswith("_") and info.name not in _NOT_DISPLAYS:
            importlib.import_module(f"{__name__}.{info.name}")
