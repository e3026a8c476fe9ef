"""Attribute values as roslaunch 1.16's loader reads them (``xmlloader.py``, ``core.Node``).

Two bool rules live side by side there: ``if``/``unless`` go through ``loader.convert_value(v,
'bool')``, which strips blanks and accepts ``true``/``false``/``1``/``0`` in any case, while
``required``, ``respawn``, ``clear_params``, ``pass_all_args`` and ``subst_value`` go through
``_bool_attr``, which accepts only ``true``/``false`` (any case). Every function raises
``ValueError`` with roslaunch's wording; the loader adds the file:line.
"""

from __future__ import annotations

__all__ = [
    "check_machine",
    "check_node",
    "check_test",
    "loose_bool",
    "strict_bool",
    "strict_float",
]

_MACHINE_DEFAULTS = ("true", "false", "never")


def loose_bool(value: str, label: str) -> bool:
    """``if``/``unless``: roslaunch's ``convert_value(value, 'bool')``."""
    text = value.lower().strip()
    if text in ("true", "1"):
        return True
    if text in ("false", "0"):
        return False
    raise ValueError(f"invalid bool value for {label}: {value!r} (valid: true, false, 1, 0)")


def strict_bool(value: str | None, default: bool, label: str) -> bool:
    """``required``, ``respawn``, ``clear_params``, ...: roslaunch's ``_bool_attr``."""
    if value is None:
        return default
    if value.lower() == "true":
        return True
    if value.lower() == "false":
        return False
    if not value:
        raise ValueError(f"bool value for {label} must be non-empty")
    raise ValueError(f"invalid bool value for {label}: {value!r} (valid: true, false)")


def strict_float(value: str | None, default: float, label: str) -> float:
    """roslaunch's ``_float_attr`` (its message for an empty value says "bool", kept)."""
    if value is None:
        return default
    if not value:
        raise ValueError(f"bool value for {label} must be non-empty")
    try:
        return float(value)
    except ValueError:
        raise ValueError(f"invalid float value for {label}: {value}") from None


def check_node(*, pkg: str, node_type: str, output: str | None, cwd: str | None) -> None:
    """What ``roslaunch.core.Node.__init__`` refuses (``required``+``respawn`` is checked by
    the caller, which has the bools)."""
    if not pkg.strip():
        raise ValueError("package must be non-empty")
    if not node_type.strip():
        raise ValueError("type must be non-empty")
    if output not in ("log", "screen", None):
        raise ValueError(f"output must be one of 'log', 'screen' (got {output!r})")
    if cwd not in ("ROS_HOME", "ros_home", "node", None):
        raise ValueError(f"cwd must be one of 'ROS_HOME', 'node' (got {cwd!r})")


def check_machine(*, default: str | None, timeout: str | None, ssh_port: str | None) -> None:
    """``_machine_tag``: ``default`` is true/false/never, ``timeout`` a positive number."""
    if (default or "false").lower() not in _MACHINE_DEFAULTS:
        raise ValueError(f"invalid value for 'default': {default} (valid: true, false, never)")
    try:
        int(ssh_port or "22")
    except ValueError:
        raise ValueError(f"'ssh-port' must be an integer: [{ssh_port}]") from None
    if timeout == "":
        raise ValueError("'timeout' cannot be empty")
    if timeout is not None:
        try:
            seconds = float(timeout)
        except ValueError:
            raise ValueError(f"'timeout' must be a number: [{timeout}]") from None
        if seconds <= 0.0:
            raise ValueError(f"'timeout' must be a positive number: [{timeout}]")


def check_test(*, time_limit: str | None, retry: str | None) -> None:
    """``_test_attrs``: an empty ``time-limit``/``retry`` means the default."""
    if time_limit:
        try:
            seconds = float(time_limit)
        except ValueError:
            raise ValueError(f"'time-limit' must be a number: [{time_limit}]") from None
        if seconds <= 0.0:
            raise ValueError("'time-limit' must be a positive number")
    if retry:
        try:
            int(retry)
        except ValueError:
            raise ValueError(f"'retry' must be a number: [{retry}]") from None
