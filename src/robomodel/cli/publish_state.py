"""``robomodel publish-state``: robot_state_publisher + joint_state_publisher for a description.

The seeds' display launch file without RViz: /robot_description, /joint_states, /tf and
/tf_static on the bus until interrupted.
"""

from __future__ import annotations

import argparse
import contextlib
import sys
from typing import Any

from robomodel.cli._bus import add_bus_arguments, context_from_args
from robomodel.cli._common import add_description_arguments, load_from_args
from robomodel.cli._verbs import verb_help
from robomodel.description.urdf.writer import urdf_to_string
from robomodel.runtime.nodes.joint_state_publisher import JointStatePublisher
from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "publish-state",
        help=verb_help("publish-state"),
    )
    add_description_arguments(parser)
    parser.add_argument("--prefix", default="", help="frame_prefix, prepended verbatim to frames")
    parser.add_argument("--namespace", default="/", help="namespace of both nodes")
    parser.add_argument("--rate", type=float, default=10.0, help="joint_state_publisher rate [Hz]")
    parser.add_argument("--delta", type=float, default=0.0, help="sweep joints by DELTA per tick")
    parser.add_argument("--duration", type=float, default=None, help="stop after S seconds")
    add_bus_arguments(parser)
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    result, loaded, _ = load_from_args(args)
    robot = result.robot
    text = loaded.urdf.decode("utf-8") if not loaded.is_xacro else urdf_to_string(robot)
    with context_from_args(args, announce="robomodel publish-state") as context:
        RobotStatePublisher(
            context, text, namespace=args.namespace, parameters={"frame_prefix": args.prefix}
        )
        jsp = JointStatePublisher(
            context,
            robot,
            namespace=args.namespace,
            parameters={"rate": args.rate, "delta": args.delta},
        )
        print(
            f"publishing robot '{robot.name}' ({len(jsp.free_joints)} movable joints) on "
            f"/robot_description, /joint_states, /tf, /tf_static via {context.transport.name}; "
            "Ctrl-C stops",
            file=sys.stderr,
        )
        with contextlib.suppress(KeyboardInterrupt):
            context.spin(duration_s=args.duration)
    return 0
