"""``rclpy.utilities``: the default context, ``ok``/``shutdown``, and argument helpers."""

from __future__ import annotations

from robomodel.clientlibs.rclpy._arguments import remove_ros_args
from robomodel.clientlibs.rclpy.context import Context

__all__ = [
    "get_available_rmw_implementations",
    "get_default_context",
    "get_rmw_implementation_identifier",
    "ok",
    "remove_ros_args",
    "shutdown",
    "timeout_sec_to_nsec",
    "try_shutdown",
]

_default_context = Context()


def get_default_context() -> Context:
    return _default_context


def ok(*, context: Context | None = None) -> bool:
    return (context or _default_context).ok()


def shutdown(*, context: Context | None = None) -> None:
    (context or _default_context).shutdown()


def try_shutdown(*, context: Context | None = None) -> None:
    (context or _default_context).try_shutdown()


def get_rmw_implementation_identifier() -> str:
    """robomodel speaks rmw_zenoh's wire."""
    return "rmw_zenoh_cpp"


def get_available_rmw_implementations() -> set[str]:
    return {"rmw_zenoh_cpp"}


def timeout_sec_to_nsec(timeout_sec: float | None) -> int:
    """rclpy's conversion: None or a negative timeout is -1 (wait for ever)."""
    if timeout_sec is None or timeout_sec < 0:
        return -1
    return int(float(timeout_sec) * 1e9)
