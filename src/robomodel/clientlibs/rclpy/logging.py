"""``rclpy.logging``: named loggers with severities, as rcutils prints them, and a node's logger
that also publishes on ``/rosout`` (the robomodel node's :class:`~robomodel.runtime.rosout.Rosout`).

A line is printed to stderr as rcutils' default format, ``[INFO] [1700000000.123456789]
[talker]: text`` (``RCUTILS_CONSOLE_OUTPUT_FORMAT`` with ``{severity}``, ``{time}``,
``{time_as_nanoseconds}``, ``{name}``, ``{message}``, ``{function_name}``, ``{file_name}``,
``{line_number}`` changes it). ``throttle_duration_sec``, ``once`` and ``skip_first`` are kept per
call site, as rcutils' macros are.
"""

from __future__ import annotations

import enum
import os
import sys
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from robomodel.runtime.rosout import Rosout

__all__ = [
    "LoggingSeverity",
    "RcutilsLogger",
    "clear_config",
    "get_logger",
    "get_logger_effective_level",
    "get_logger_level",
    "get_logging_directory",
    "get_logging_severity_from_string",
    "initialize",
    "set_logger_level",
    "shutdown",
]


class LoggingSeverity(enum.IntEnum):
    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


_DEFAULT_FORMAT = "[{severity}] [{time}] [{name}]: {message}"
_levels: dict[str, LoggingSeverity] = {}  # explicitly set levels by logger name
_default_level = [LoggingSeverity.INFO]
_lock = threading.Lock()


def get_logging_severity_from_string(log_severity: str) -> LoggingSeverity:
    try:
        return LoggingSeverity[log_severity.upper().replace("WARNING", "WARN")]
    except KeyError:
        names = ", ".join(s.name.lower() for s in LoggingSeverity if s)
        raise ValueError(
            f"unknown log severity '{log_severity}'; severities are: {names}"
        ) from None


def _severity(level: Any) -> LoggingSeverity:
    return (
        get_logging_severity_from_string(level)
        if isinstance(level, str)
        else LoggingSeverity(level)
    )


def set_logger_level(name: str, level: Any, detailed_error: bool = False) -> None:
    """The level of logger ``name`` (and of its children that have none of their own)."""
    with _lock:
        _levels[name] = _severity(level)


def get_logger_effective_level(name: str) -> LoggingSeverity:
    """The level set on ``name`` or its nearest ancestor (``a.b`` inherits from ``a``), else
    the default (INFO, or ``--log-level``)."""
    while name:
        level = _levels.get(name)
        if level is not None and level != LoggingSeverity.UNSET:
            return level
        name = name.rpartition(".")[0]
    return _default_level[0]


def get_logger_level(name: str) -> LoggingSeverity:
    """The level set on logger ``name`` itself (UNSET when none was)."""
    return _levels.get(name, LoggingSeverity.UNSET)


def set_default_level(level: Any) -> None:
    """The level of loggers without one (``--ros-args --log-level LEVEL``)."""
    _default_level[0] = _severity(level)


def initialize() -> None:
    """Nothing to set up: loggers print from their first use."""


def shutdown() -> None:
    """Nothing to tear down (rcutils' logging has no state robomodel keeps)."""


def clear_config() -> None:
    """Forget the levels set (rcutils' ``clear_config``)."""
    with _lock:
        _levels.clear()
        _default_level[0] = LoggingSeverity.INFO


def get_logging_directory() -> str:
    """Where rcl would write log files (``ROS_LOG_DIR``, else ``ROS_HOME/log``)."""
    explicit = os.environ.get("ROS_LOG_DIR")
    if explicit:
        return os.path.expanduser(explicit)
    home = os.environ.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")
    return os.path.join(home, "log")


class RcutilsLogger:
    """A logger by name (``get_logger("talker")``, ``node.get_logger()``)."""

    def __init__(
        self, name: str = "", *, rosout: Callable[[], Rosout | None] | None = None
    ) -> None:
        self.name = name
        self._rosout = rosout
        self._sites: dict[tuple[str, int, str], list[float]] = {}  # call site -> [last, count]

    def get_child(self, name: str) -> RcutilsLogger:
        if not name:
            raise ValueError("Child logger name must not be empty.")
        full = f"{self.name}.{name}" if self.name else name
        return RcutilsLogger(full, rosout=self._rosout)

    def set_level(self, level: Any) -> None:
        set_logger_level(self.name, level)

    def get_effective_level(self) -> LoggingSeverity:
        return get_logger_effective_level(self.name)

    def is_enabled_for(self, severity: Any) -> bool:
        return _severity(severity) >= self.get_effective_level()

    def log(
        self,
        message: Any,
        severity: Any,
        *,
        name: str | None = None,
        throttle_duration_sec: float | None = None,
        throttle_time_source_type: Any = None,
        once: bool = False,
        skip_first: bool = False,
    ) -> bool:
        """Log ``message`` at ``severity``; True if it was printed (rclpy's return)."""
        level = _severity(severity)
        if not self.is_enabled_for(level):
            return False
        frame = sys._getframe(2 if _is_wrapper(sys._getframe(1)) else 1)
        site = (frame.f_code.co_filename, frame.f_lineno, frame.f_code.co_name)
        if once or skip_first or throttle_duration_sec:
            with _lock:
                state = self._sites.setdefault(site, [-float("inf"), 0.0])
                state[1] += 1
                if once and state[1] > 1:
                    return False
                if skip_first and state[1] == 1:
                    return False
                now = time.monotonic()
                if throttle_duration_sec and now - state[0] < throttle_duration_sec:
                    return False
                state[0] = now
        text = str(message)
        _print(level, name or self.name, text, site)
        rosout = self._rosout() if self._rosout is not None else None  # None once destroyed
        if rosout is not None:
            rosout.publish(int(level), text, file=site[0], function=site[2], line=site[1])
        return True

    def debug(self, message: Any, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.DEBUG, **kwargs)

    def info(self, message: Any, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.INFO, **kwargs)

    def warning(self, message: Any, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.WARN, **kwargs)

    warn = warning

    def error(self, message: Any, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.ERROR, **kwargs)

    def fatal(self, message: Any, **kwargs: Any) -> bool:
        return self.log(message, LoggingSeverity.FATAL, **kwargs)


_WRAPPERS = {"debug", "info", "warning", "error", "fatal"}


def _is_wrapper(frame: Any) -> bool:
    return frame.f_code.co_filename == __file__ and frame.f_code.co_name in _WRAPPERS


def _print(level: LoggingSeverity, name: str, text: str, site: tuple[str, int, str]) -> None:
    now_ns = time.time_ns()
    fields = {
        "severity": level.name,
        "time": f"{now_ns // 1_000_000_000}.{now_ns % 1_000_000_000:09d}",
        "time_as_nanoseconds": str(now_ns),
        "name": name,
        "message": text,
        "function_name": site[2],
        "file_name": site[0],
        "line_number": str(site[1]),
    }
    line = os.environ.get("RCUTILS_CONSOLE_OUTPUT_FORMAT") or _DEFAULT_FORMAT
    for key, value in fields.items():
        line = line.replace("{" + key + "}", value)
    stream = sys.stdout if os.environ.get("RCUTILS_LOGGING_USE_STDOUT") == "1" else sys.stderr
    try:
        stream.write(line + "\n")
        if os.environ.get("RCUTILS_LOGGING_BUFFERED_STREAM") != "1":
            stream.flush()
    except (OSError, ValueError):  # a closed stream (a pipe whose reader left) never raises
        pass


def get_logger(name: str) -> RcutilsLogger:
    """A logger of this name (rclpy's ``rclpy.logging.get_logger``)."""
    if not name:
        raise ValueError("Logger name must not be empty.")
    return RcutilsLogger(name)
