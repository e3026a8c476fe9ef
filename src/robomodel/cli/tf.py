"""``robomodel tf``: what ``tf2_echo SOURCE TARGET`` prints.

Static mode, ``robomodel tf FILE SOURCE TARGET``: the model's transforms are computed as
robot_state_publisher would publish them (fixed joints static, movable joints stamped at time 0)
into a tf2-style buffer, which is asked ``lookup_transform(SOURCE, TARGET)`` as tf2_echo does
(its first argument is the target frame of the lookup). All stamps are 0: ``At time 0.0``.

Live mode, ``robomodel tf SOURCE TARGET``: listens to /tf and /tf_static on the bus and prints
the block at ``--rate`` Hz (1 by default, as tf2_echo), waiting with tf2_echo's message while
the transform is not available.
"""

from __future__ import annotations

import argparse
import sys
import time
from typing import Any

from robomodel.cli._bus import add_bus_arguments, context_from_args
from robomodel.cli._common import add_package_options
from robomodel.cli._joints import (
    add_joint_arguments,
    configuration_from_args,
    kinematics_from_args,
)
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError
from robomodel.tf import TransformError, buffer_from_model, format_echo

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "tf",
        help=verb_help("tf"),
        description=(
            "Print what 'tf2_echo SOURCE TARGET' prints: the pose of TARGET in SOURCE. With a "
            "FILE, for the robot at the joint values given (others at joint_state_publisher's "
            "defaults); without one, live from /tf and /tf_static on the bus."
        ),
    )
    parser.add_argument(
        "words",
        nargs="+",
        metavar="[FILE] SOURCE TARGET [name:=value ...]",
        help="description file (static mode), frames, and xacro arguments",
    )
    add_package_options(parser, mappings=False)
    add_joint_arguments(parser)
    parser.add_argument(
        "--frame-prefix",
        default="",
        metavar="PREFIX",
        help="prepended verbatim to every frame, as robot_state_publisher's frame_prefix",
    )
    parser.add_argument("--rate", type=float, default=1.0, help="live mode: echo rate [Hz]")
    parser.add_argument("--once", action="store_true", help="live mode: print one block and exit")
    parser.add_argument("--timeout", type=float, default=None, help="live mode: give up after S s")
    add_bus_arguments(parser)
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    positionals = [w for w in args.words if ":=" not in w]
    args.mappings = [w for w in args.words if ":=" in w]
    if len(positionals) == 3:
        args.file, args.source, args.target = positionals
        return _run_static(args)
    if len(positionals) == 2:
        if args.mappings or args.joint:
            raise RobomodelError("name:=value and --joint need a description FILE (static mode)")
        args.source, args.target = positionals
        return _run_live(args)
    raise RobomodelError(
        "expected SOURCE TARGET (live, from the bus) or FILE SOURCE TARGET (from a description)"
    )


def _run_static(args: argparse.Namespace) -> int:
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


def _run_live(args: argparse.Namespace) -> int:
    from robomodel.runtime.tf_listener import TransformListener

    if not args.rate > 0:
        raise RobomodelError(f"Failed to convert rate argument '{args.rate}' to a positive rate")
    with context_from_args(args, announce=None if args.once else "robomodel tf") as context:
        node = context.create_node("tf2_echo")
        buffer = TransformListener(node).buffer
        deadline = None if args.timeout is None else time.monotonic() + args.timeout
        last_wait = -1.0
        try:
            while deadline is None or time.monotonic() < deadline:
                try:
                    transform = buffer.lookup_transform(args.source, args.target)
                except TransformError as exc:
                    now = time.monotonic()
                    if now - last_wait >= 1.0:  # tf2_echo throttles this to once a second
                        print(
                            f"Waiting for transform {args.source} ->  {args.target}: {exc}",
                            file=sys.stderr,
                        )
                        last_wait = now
                    context.spin(duration_s=0.1)
                    continue
                sys.stdout.write(format_echo(transform))
                sys.stdout.flush()
                if args.once:
                    return 0
                context.spin(duration_s=1.0 / args.rate)
        except KeyboardInterrupt:
            return 0
    return 1 if args.once else 0
