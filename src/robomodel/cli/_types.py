"""Options of the verbs that take any message type: where interface packages are and which
distribution's common interfaces to use (see :mod:`robomodel.runtime.msg._resolver`)."""

from __future__ import annotations

import argparse

__all__ = ["add_type_arguments", "apply_type_arguments"]


def add_type_arguments(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("message types")
    group.add_argument(
        "--package-path",
        dest="type_package_path",
        action="append",
        default=[],
        metavar="DIR",
        help="also find interface packages (msg/, srv/, action/) under DIR (besides ROS_PACKAGE_PATH "
        "and AMENT_PREFIX_PATH)",
    )
    group.add_argument(
        "--distro",
        default=None,
        choices=("humble", "iron", "jazzy", "kilted", "lyrical"),  # rosbags' ROS 2 stores
        help="the ROS 2 distribution of the common interfaces (default: ROS_DISTRO, else jazzy)",
    )


def apply_type_arguments(args: argparse.Namespace) -> None:
    """Hand ``--package-path``/``--distro`` to the type resolver (if the verb has them)."""
    paths = getattr(args, "type_package_path", None)
    distro = getattr(args, "distro", None)
    if not paths and distro is None:
        return
    from robomodel.runtime.msg._resolver import configure

    configure(package_paths=tuple(paths or ()), distro=distro)
