"""Errors of the viewer."""

from __future__ import annotations

from robomodel.errors import RobomodelError

__all__ = ["MeshLoadError", "PortInUseError", "ViewerError"]


class ViewerError(RobomodelError):
    """Root of the viewer's errors."""


class PortInUseError(ViewerError):
    """The TCP port asked for is taken by another program."""

    def __init__(self, host: str, port: int, free_port: int | None) -> None:
        self.host = host
        self.port = port
        self.free_port = free_port
        hint = f"try --port {free_port}" if free_port is not None else "try another --port"
        super().__init__(
            f"port {port} on {host} is already in use (another viewer or server?); {hint}"
        )


class MeshLoadError(ViewerError):
    """A mesh file exists but cannot be read as a mesh."""

    def __init__(self, path: str, reason: str) -> None:
        self.path = path
        self.reason = reason
        super().__init__(f"cannot load mesh '{path}': {reason}")
