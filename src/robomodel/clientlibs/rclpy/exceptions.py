"""rclpy's exceptions (``rclpy.exceptions``), raised where rclpy raises them."""

from __future__ import annotations

from typing import Any

__all__ = [
    "InvalidHandle",
    "InvalidNamespaceException",
    "InvalidNodeNameException",
    "InvalidParameterException",
    "InvalidParameterTypeException",
    "InvalidParameterValueException",
    "InvalidServiceNameException",
    "InvalidTopicNameException",
    "NotInitializedException",
    "ParameterAlreadyDeclaredException",
    "ParameterException",
    "ParameterImmutableException",
    "ParameterNotDeclaredException",
    "ParameterUninitializedException",
    "ROSInterruptException",
]


class NotInitializedException(Exception):
    """rclpy was used before ``rclpy.init()`` (or after ``rclpy.shutdown()``)."""

    def __init__(self, *args: Any) -> None:
        super().__init__("rclpy.init() has not been called", *args)


class InvalidHandle(Exception):
    """A destroyed entity was used."""


class ROSInterruptException(Exception):
    """The context was shut down while waiting (``Rate.sleep``, ``Clock.sleep_for``)."""


class InvalidNodeNameException(ValueError):
    """A node name ROS 2 refuses."""


class InvalidNamespaceException(ValueError):
    """A namespace ROS 2 refuses."""


class InvalidTopicNameException(ValueError):
    """A topic name ROS 2 refuses."""


class InvalidServiceNameException(ValueError):
    """A service name ROS 2 refuses."""


class ParameterException(Exception):
    """Base of the parameter errors."""

    def __init__(self, error_msg: str, parameters: Any = None) -> None:
        super().__init__(error_msg if parameters is None else f"{error_msg}: {parameters}")


class ParameterNotDeclaredException(ParameterException):
    def __init__(self, parameters: Any) -> None:
        super().__init__("Invalid access to undeclared parameter(s)", parameters)


class ParameterAlreadyDeclaredException(ParameterException):
    def __init__(self, parameters: Any) -> None:
        super().__init__("Parameter(s) already declared", parameters)


class ParameterUninitializedException(ParameterException):
    def __init__(self, parameter_name: str) -> None:
        super().__init__(f"The parameter '{parameter_name}' is not initialized")


class InvalidParameterException(ParameterException):
    def __init__(self, parameter: Any) -> None:
        super().__init__("Invalid parameter name", parameter)


class InvalidParameterValueException(ParameterException):
    def __init__(self, parameter: Any, value: Any, reason: str) -> None:
        super().__init__(f"Invalid parameter value ({value!r}) for parameter. Reason: {reason}",
                         parameter)  # fmt: skip


class InvalidParameterTypeException(ParameterException):
    def __init__(self, desired_parameter: Any, expected_type: str) -> None:
        super().__init__(f"Trying to set parameter to a value of type {expected_type}",
                         desired_parameter)  # fmt: skip


class ParameterImmutableException(ParameterException):
    def __init__(self, parameter_name: str) -> None:
        super().__init__(f"Attempted to modify read-only parameter '{parameter_name}'")
