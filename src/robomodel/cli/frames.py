"""``robomodel frames``: the TF tree as view_frames draws it (static mode, from a model)."""

from __future__ import annotations

import argparse
import sys
import time
from typing import Any

from robomodel._atomic import atomic_write_text
from robomodel.cli._joints import (
    add_joint_arguments,
    add_package_options,
    configuration_from_args,
    kinematics_from_args,
)
from robomodel.cli.graph import render_dot
from robomodel.tf import buffer_from_model, frames_dot

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "frames",
        help="draw the TF tree, as view_frames does",
        description=(
            "Write view_frames' graph of the transforms robot_state_publisher would publish "
            "for the model. Without -o the .gv text goes to stdout; -o FILE.pdf|.svg|.png "
            "renders it with Graphviz's dot."
        ),
    )
    parser.add_argument("file", metavar="FILE", help="a .urdf or .xacro file")
    add_package_options(parser)
    add_joint_arguments(parser)
    parser.add_argument("-o", "--output", metavar="OUT", help="output file (.gv, .svg, .pdf, .png)")
    parser.add_argument("--frame-prefix", default="", metavar="PREFIX", help="frame_prefix")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    kin = kinematics_from_args(args)
    q = configuration_from_args(kin, args.joint)
    buffer = buffer_from_model(kin, q, frame_prefix=args.frame_prefix)
    text = frames_dot(buffer, recorded_time_s=time.time())
    if args.output is None:
        sys.stdout.write(text + "\n")
        return 0
    if args.output.endswith((".gv", ".dot")):
        atomic_write_text(args.output, text)
    else:
        render_dot(text, args.output)
    print(f"Created file {args.output}")
    return 0
