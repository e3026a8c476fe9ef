"""The bridges' errors."""

from __future__ import annotations

from robomodel.errors import RobomodelError

__all__ = ["BridgeError", "ClientError"]


class BridgeError(RobomodelError):
    """A bridge that cannot start (a port in use, a bad parameter)."""


class ClientError(RobomodelError):
    """A client's request the bridge refuses (bad JSON, an invalid name, an unknown type); the
    client is told, the bridge goes on."""
