"""What the rclpy modules share: the interface classes of the user's flavour, and the error for
the rclpy calls robomodel does not offer."""

from __future__ import annotations

import importlib
from typing import Any, NoReturn

__all__ = ["interface", "not_offered"]


def interface(module: str, name: str) -> Any:
    """A message or service class as user code gets it (``interface("builtin_interfaces.msg",
    "Time")``): through the import finder, so of the flavour user code sees."""
    return getattr(importlib.import_module(module), name)


def not_offered(call: str, instead: str = "") -> NoReturn:
    """Raise NotImplementedError naming ``call`` (robomodel never makes it a silent no-op)."""
    more = f"; {instead}" if instead else ""
    raise NotImplementedError(f"{call} is not offered by robomodel's rclpy{more}")
