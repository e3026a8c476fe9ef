"""Checking that the TCP port is free before serving (viser would silently take the next)."""

from __future__ import annotations

import socket

from robomodel.viewer.errors import PortInUseError

__all__ = ["ensure_port_free", "port_is_free"]


def port_is_free(host: str, port: int) -> bool:
    """Whether a server could bind ``host:port`` now (SO_REUSEADDR, as asyncio servers use)."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as sock:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            sock.bind((host, port))
        except OSError:
            return False
    return True


def ensure_port_free(host: str, port: int, *, search: int = 50) -> None:
    """Raise :class:`PortInUseError` (suggesting a free port nearby) if ``port`` is taken."""
    if port == 0 or port_is_free(host, port):
        return
    free = next(
        (p for p in range(port + 1, min(port + 1 + search, 65536)) if port_is_free(host, p)),
        None,
    )
    raise PortInUseError(host, port, free)
