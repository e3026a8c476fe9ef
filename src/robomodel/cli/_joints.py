"""Arguments shared by the kinematics verbs (tf, frames, fk, ik)."""

from __future__ import annotations

import argparse
import math

import numpy as np
from numpy.typing import NDArray

from robomodel.cli._common import load_from_args
from robomodel.errors import RobomodelError
from robomodel.kinematics import Kinematics
from robomodel.tf.robot_state import joint_state_defaults

__all__ = [
    "add_joint_arguments",
    "configuration_from_args",
    "kinematics_from_args",
]


def add_joint_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--joint",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help=(
            "joint position [rad or m] (repeatable); others start where joint_state_publisher "
            "puts them: 0, or the middle of the limits when 0 is outside them"
        ),
    )


def kinematics_from_args(args: argparse.Namespace) -> Kinematics:
    result, _, _ = load_from_args(args)
    # A command computes a handful of poses: importing MuJoCo (~0.1 s) would cost more than
    # it saves.
    return Kinematics(result.robot, backend="numpy")


def configuration_from_args(kin: Kinematics, items: list[str]) -> NDArray[np.float64]:
    """``q`` from ``--joint NAME=VALUE`` items over joint_state_publisher's defaults."""
    values: dict[str, float] = dict(joint_state_defaults(kin))
    for item in items:
        name, sep, text = item.partition("=")
        if not sep or not name:
            raise RobomodelError(f"--joint takes NAME=VALUE, not '{item}'")
        try:
            value = float(text)
        except ValueError:
            raise RobomodelError(f"--joint {name}: '{text}' is not a number") from None
        if not math.isfinite(value):
            raise RobomodelError(f"--joint {name}: the value must be finite, not '{text}'")
        values[name] = value
    return kin.q_from_dict(values)
