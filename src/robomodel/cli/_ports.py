"""The viewer's ``--port``: 8080 by default, or ``ROBOMODEL_VIEWER_PORT`` (0: any free port).

On a shared machine every user's viewer would otherwise ask for 8080; the variable gives each
shell its own default, as ``ROS_MASTER_URI`` and ``ROS_DOMAIN_ID`` do for the graph. argparse
converts a string default with the option's ``type``, so a bad value in the variable is the same
clear error (exit 2) as a bad ``--port``.
"""

from __future__ import annotations

import os

TYPE_CHECKING = False
if TYPE_CHECKING:
    import argparse

__all__ = ["ENV_VIEWER_PORT", "add_port_argument", "port_number"]

ENV_VIEWER_PORT = "ROBOMODEL_VIEWER_PORT"


def port_number(text: str) -> int:
    """A TCP port, 0-65535 (0: any free port)."""
    import argparse

    try:
        port = int(text)
    except ValueError:
        port = -1
    if not 0 <= port <= 65535:
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a TCP port (0-65535, 0: any free port; the default comes from "
            f"{ENV_VIEWER_PORT} when it is set)"
        )
    return port


def add_port_argument(parser: argparse.ArgumentParser, help: str) -> None:
    """``--port``, defaulting to ``ROBOMODEL_VIEWER_PORT`` or 8080."""
    parser.add_argument(
        "--port",
        type=port_number,
        default=os.environ.get(ENV_VIEWER_PORT, "8080"),
        help=f"{help} (default: ${ENV_VIEWER_PORT}, else 8080; 0: any free port)",
    )
