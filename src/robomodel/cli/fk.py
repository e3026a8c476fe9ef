"""``robomodel fk``: link poses in the root frame at given joint values."""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

from robomodel.cli._common import add_package_options
from robomodel.cli._joints import (
    add_joint_arguments,
    configuration_from_args,
    kinematics_from_args,
)
from robomodel.cli._verbs import verb_help
from robomodel.kinematics.se3 import quat_xyzw_from_matrix, rpy_from_matrix

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "fk",
        help=verb_help("fk"),
        description="Print the pose of every link (or of --link LINK) in the root link's frame.",
    )
    parser.add_argument("file", metavar="FILE", help="a .urdf or .xacro file")
    add_package_options(parser)
    add_joint_arguments(parser)
    parser.add_argument(
        "--link", action="append", default=[], metavar="LINK", help="only this link (repeatable)"
    )
    parser.add_argument("--json", action="store_true", help="machine-readable output")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    kin = kinematics_from_args(args)
    q = configuration_from_args(kin, args.joint)
    links = args.link or list(kin.link_names)
    Ts = kin.fk(q, links=links)
    rpy = rpy_from_matrix(Ts[:, :3, :3])
    quat = quat_xyzw_from_matrix(Ts[:, :3, :3])
    if args.json:
        doc = {
            "root": kin.root_link,
            "joints": {
                name: float(q[kin.q_slice(name)][0])
                for name in kin.joint_names
                if kin.q_slice(name).stop - kin.q_slice(name).start == 1
            },
            "links": {
                link: {
                    "xyz": Ts[i, :3, 3].tolist(),
                    "rpy": rpy[i].tolist(),
                    "quat_xyzw": quat[i].tolist(),
                    "matrix": Ts[i].tolist(),
                }
                for i, link in enumerate(links)
            },
        }
        json.dump(doc, sys.stdout, indent=2)
        sys.stdout.write("\n")
        return 0
    width = max(len(link) for link in links)
    print(f"poses in '{kin.root_link}' (xyz [m], rpy [rad])")
    for i, link in enumerate(links):
        xyz = " ".join(f"{v:9.5f}" for v in Ts[i, :3, 3])
        angles = " ".join(f"{v:9.5f}" for v in rpy[i])
        print(f"{link:<{width}}  xyz {xyz}  rpy {angles}")
    return 0
