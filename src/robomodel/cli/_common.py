"""Arguments shared by the verbs that read a robot description.

Adding the arguments imports nothing of the description layer (lxml with it): a verb whose
parser offers them to one sub-verb (``control run``) does not load it for the others
(``control list-controllers``). Reading the description does.
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from robomodel.errors import RobomodelError

if TYPE_CHECKING:
    from robomodel.description.packages import PackageIndex
    from robomodel.description.urdf.reader import ParseResult
    from robomodel.loading import LoadedDescription

__all__ = [
    "add_description_arguments",
    "add_package_options",
    "load_from_args",
    "package_index_from_args",
    "split_mappings",
]


def add_description_arguments(parser: argparse.ArgumentParser) -> None:
    """``FILE [name:=value ...] [--package-path DIR] [--package NAME=DIR]``."""
    parser.add_argument("file", metavar="FILE", help="a .urdf or .xacro file")
    add_package_options(parser)


def add_package_options(parser: argparse.ArgumentParser, *, mappings: bool = True) -> None:
    """``[name:=value ...] --package-path DIR --package NAME=DIR`` (after the positionals)."""
    if mappings:
        parser.add_argument(
            "mappings", nargs="*", metavar="name:=value", help="xacro arguments (for .xacro files)"
        )
    parser.add_argument(
        "--package-path",
        action="append",
        default=[],
        metavar="DIR",
        help="directory to search recursively for ROS packages (repeatable)",
    )
    parser.add_argument(
        "--package",
        action="append",
        default=[],
        metavar="NAME=DIR",
        help="where package NAME lives (repeatable; overrides search)",
    )


def add_frame_rate_argument(parser: argparse.ArgumentParser) -> None:
    """``--frame-rate HZ``: the viewer's scene updates per second at most (RViz's Frame Rate)."""

    def hertz(text: str) -> float:
        value = float(text)
        if not 1.0 <= value <= 1000.0:
            raise argparse.ArgumentTypeError(f"must be 1..1000 Hz, got {text}")
        return value

    parser.add_argument(
        "--frame-rate",
        type=hertz,
        default=60.0,
        metavar="HZ",
        help="the viewer's scene updates per second at most (RViz's Frame Rate, default 60)",
    )


def split_inputs(items: list[str], verb: str) -> tuple[list[str], dict[str, str]]:
    """``FILE ... name:=value ...`` (in any order) as the files and the xacro arguments."""
    files = [item for item in items if ":=" not in item]
    if not files:
        raise RobomodelError(f"robomodel {verb} needs at least one .urdf or .xacro FILE")
    return files, split_mappings([item for item in items if ":=" in item])


def split_mappings(items: list[str]) -> dict[str, str]:
    """Turn ``name:=value`` arguments into a dict (as xacro and ros2 launch do)."""
    mappings: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition(":=")
        if not sep or not name:
            raise RobomodelError(
                f"unexpected argument '{item}'; xacro arguments are written name:=value"
            )
        mappings[name] = value
    return mappings


def package_index_from_args(args: argparse.Namespace) -> PackageIndex:
    from robomodel.description.packages import index_from_options

    return index_from_options(args.package_path, args.package)


def load_from_args(
    args: argparse.Namespace,
) -> tuple[ParseResult, LoadedDescription, PackageIndex]:
    """Expand and parse the description named on the command line."""
    from robomodel.loading import read_description

    index = package_index_from_args(args).with_workspace_of(args.file)
    result, loaded = read_description(
        args.file, args=split_mappings(args.mappings), package_index=index
    )
    return result, loaded, index
