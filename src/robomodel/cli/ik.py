"""``robomodel ik``: joint values that put a link at a pose (numerical, or all analytic ones)."""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

import numpy as np

from robomodel.cli._common import add_package_options
from robomodel.cli._joints import kinematics_from_args
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError
from robomodel.kinematics.se3 import transform_from_xyz_rpy

__all__ = ["EXIT_UNREACHABLE", "register"]

EXIT_UNREACHABLE = 1


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "ik",
        help=verb_help("ik"),
        description=(
            "Find joint values inside the limits that put LINK at --xyz (and --rpy, else the "
            "orientation is free). --all lists every analytic solution (UR-type arms). Exit "
            "status 1 when the target is unreachable."
        ),
    )
    parser.add_argument("file", metavar="FILE", help="a .urdf or .xacro file")
    add_package_options(parser)
    parser.add_argument("--link", required=True, metavar="LINK", help="the link to place")
    parser.add_argument(
        "--xyz",
        required=True,
        nargs=3,
        type=float,
        metavar=("X", "Y", "Z"),
        help="target position in the root frame [m]",
    )
    parser.add_argument(
        "--rpy",
        nargs=3,
        type=float,
        metavar=("R", "P", "Y"),
        help="target roll pitch yaw in the root frame [rad]",
    )
    parser.add_argument("--all", action="store_true", help="all analytic solutions")
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    parser.add_argument("--seed", type=int, default=0, help="random seed for the restarts")
    parser.set_defaults(func=run)


def _print(kin: Any, solutions: list[np.ndarray], as_json: bool, extra: dict[str, Any]) -> None:
    rows = [{name: float(q[kin.q_slice(name)][0]) for name in kin.joint_names} for q in solutions]
    if as_json:
        json.dump({**extra, "solutions": rows}, sys.stdout, indent=2)
        sys.stdout.write("\n")
        return
    width = max((len(n) for n in kin.joint_names), default=0)
    for k, row in enumerate(rows):
        if len(rows) > 1:
            print(f"solution {k + 1}:")
        for name, value in row.items():
            print(f"  {name:<{width}}  {value: .6f}")


def run(args: argparse.Namespace) -> int:
    kin = kinematics_from_args(args)
    if args.all and args.rpy is None:
        raise RobomodelError("--all needs a full pose: give --rpy too")
    rpy = (0.0, 0.0, 0.0) if args.rpy is None else tuple(args.rpy)
    T = transform_from_xyz_rpy(args.xyz, rpy)
    if args.all:
        solutions = kin.analytic_ik(T, args.link)
        if len(solutions) == 0:
            print(
                f"robomodel: '{args.link}' cannot reach the target (no analytic solution "
                "inside the limits)",
                file=sys.stderr,
            )
            return EXIT_UNREACHABLE
        _print(kin, list(solutions), args.json, {"link": args.link, "analytic": True})
        return 0
    result = kin.ik(T, args.link, position_only=args.rpy is None, rng=args.seed)
    if not result.success:
        print(
            f"robomodel: '{args.link}' cannot reach the target: best attempt is "
            f"{result.position_error_m:.3g} m and {result.rotation_error_rad:.3g} rad away "
            f"after {result.attempts} attempts",
            file=sys.stderr,
        )
        return EXIT_UNREACHABLE
    _print(
        kin,
        [result.q],
        args.json,
        {
            "link": args.link,
            "analytic": False,
            "position_error_m": result.position_error_m,
            "rotation_error_rad": result.rotation_error_rad,
        },
    )
    return 0
