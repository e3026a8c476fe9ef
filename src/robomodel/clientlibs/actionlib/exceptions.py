"""actionlib's exception."""

from __future__ import annotations

from robomodel.clientlibs.rospy.exceptions import ROSException

__all__ = ["ActionException"]


class ActionException(ROSException):
    """A class given as an action that is none (``ActionServer(ns, FibonacciGoal, ...)``)."""
