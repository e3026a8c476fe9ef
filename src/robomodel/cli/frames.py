"""``robomodel frames``: the TF tree as view_frames draws it, from a model or live from the bus."""

from __future__ import annotations

import argparse
import contextlib
import sys
import time
from typing import Any

from robomodel._atomic import atomic_write_text
from robomodel.cli._bus import add_bus_arguments, context_from_args, wait_for_peers
from robomodel.cli._common import add_package_options
from robomodel.cli._joints import (
    add_joint_arguments,
    configuration_from_args,
    kinematics_from_args,
)
from robomodel.cli._verbs import verb_help
from robomodel.cli.graph import render_dot
from robomodel.errors import RobomodelError
from robomodel.tf import BufferCore, buffer_from_model, frames_dot

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "frames",
        help=verb_help("frames"),
        description=(
            "Write view_frames' graph of the transforms robot_state_publisher would publish "
            "for the model. Without -o the .gv text goes to stdout; -o FILE.pdf|.svg|.png "
            "renders it with Graphviz's dot."
        ),
    )
    parser.add_argument(
        "file", metavar="FILE", nargs="?", help="a .urdf or .xacro file (omit with --live)"
    )
    add_package_options(parser)
    add_joint_arguments(parser)
    parser.add_argument("-o", "--output", metavar="OUT", help="output file (.gv, .svg, .pdf, .png)")
    parser.add_argument("--frame-prefix", default="", metavar="PREFIX", help="frame_prefix")
    parser.add_argument(
        "--live", action="store_true", help="listen to /tf and /tf_static on the bus instead"
    )
    parser.add_argument(
        "-t",
        "--wait-time",
        type=float,
        default=5.0,
        metavar="SECONDS",
        help="with --live: how long to listen (view_frames' default: 5 s)",
    )
    add_bus_arguments(parser)
    parser.set_defaults(func=run)


def _live_buffer(args: argparse.Namespace) -> BufferCore:
    from robomodel.runtime.tf_listener import TransformListener

    if args.file is not None or args.mappings or args.joint:
        raise RobomodelError("--live listens to the bus: give no FILE, name:=value or --joint")
    print(f"Listening to tf data for {args.wait_time} seconds...", file=sys.stderr)
    with context_from_args(args) as context:
        listener = TransformListener(context.create_node("view_frames"))
        # the listening time counts once this session has linked up with the others (a
        # loaded machine can take seconds), as view_frames' node is up before it listens
        wait_for_peers(context, timeout_s=5.0)
        with contextlib.suppress(KeyboardInterrupt):
            context.spin(duration_s=args.wait_time)
    return listener.buffer


def run(args: argparse.Namespace) -> int:
    if args.live:
        buffer = _live_buffer(args)
    else:
        if args.file is None:
            raise RobomodelError("give a description FILE, or --live to listen to the bus")
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
