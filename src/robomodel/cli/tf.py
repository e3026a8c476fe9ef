"""``robomodel tf``: what ``tf2_echo SOURCE TARGET`` prints, for a model at given joint values.

Static mode: the model's transforms are computed as robot_state_publisher would publish them
(fixed joints static, movable joints stamped at time 0) into a tf2-style buffer, which is then
asked ``lookup_transform(SOURCE, TARGET)`` exactly as tf2_echo does (its first argument is the
target frame of the lookup). All stamps are 0, so the block starts ``At time 0.0``.
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from robomodel.cli._joints import (
    add_joint_arguments,
    add_package_options,
    configuration_from_args,
    kinematics_from_args,
)
from robomodel.tf import TransformError, buffer_from_model, format_echo

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "tf",
        help="print the transform between two frames, as tf2_echo does",
        description=(
            "Print what 'tf2_echo SOURCE TARGET' prints: the pose of TARGET in SOURCE (the "
            "transform that takes data from TARGET into SOURCE), with the robot at the joint "
            "values given (others at joint_state_publisher's defaults)."
        ),
    )
    parser.add_argument("file", metavar="FILE", help="a .urdf or .xacro file")
    parser.add_argument("source", metavar="SOURCE", help="source frame (tf2_echo's first argument)")
    parser.add_argument("target", metavar="TARGET", help="target frame (tf2_echo's second)")
    add_package_options(parser)
    add_joint_arguments(parser)
    parser.add_argument(
        "--frame-prefix",
        default="",
        metavar="PREFIX",
        help="prepended verbatim to every frame, as robot_state_publisher's frame_prefix",
    )
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    kin = kinematics_from_args(args)
    q = configuration_from_args(kin, args.joint)
    buffer = buffer_from_model(kin, q, frame_prefix=args.frame_prefix)
    try:
        transform = buffer.lookup_transform(args.source, args.target)
    except TransformError as exc:
        raise TransformError(
            f"{exc}\nThe current list of frames is:\n{buffer.all_frames_as_string()}".rstrip()
        ) from None
    sys.stdout.write(format_echo(transform))
    return 0
