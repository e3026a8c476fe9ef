"""``robomodel new``: create a robot description package."""

from __future__ import annotations

import argparse
from typing import Any

from robomodel.cli._verbs import verb_help
from robomodel.description.scaffold import create_description_package

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "new",
        help=verb_help("new"),
    )
    parser.add_argument("name", metavar="NAME_description", help="package name")
    parser.add_argument("--dir", default=".", help="where to create it (default: .)")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    target = create_description_package(args.name, args.dir)
    robot = args.name.removesuffix("_description")
    print(f"Created {target}")
    print(f"  check it:  robomodel check {target}/urdf/{robot}.urdf")
    return 0
