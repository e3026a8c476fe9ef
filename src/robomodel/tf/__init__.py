"""TF: a tf2-style transform buffer, robot_state_publisher's transforms, tf2_echo and view_frames."""

from robomodel.tf.buffer import DEFAULT_CACHE_TIME_NS, BufferCore, TFWarning
from robomodel.tf.echo import format_echo
from robomodel.tf.exceptions import (
    BackwardExtrapolationError,
    ConnectivityError,
    ExtrapolationError,
    ForwardExtrapolationError,
    InvalidArgumentError,
    LookupError,
    NoDataForExtrapolationError,
    TransformError,
)
from robomodel.tf.message import TransformStamped
from robomodel.tf.robot_state import buffer_from_model, joint_state_defaults, robot_transforms
from robomodel.tf.view_frames import frames_dot

__all__ = [
    "DEFAULT_CACHE_TIME_NS",
    "BackwardExtrapolationError",
    "BufferCore",
    "ConnectivityError",
    "ExtrapolationError",
    "ForwardExtrapolationError",
    "InvalidArgumentError",
    "LookupError",
    "NoDataForExtrapolationError",
    "TFWarning",
    "TransformError",
    "TransformStamped",
    "buffer_from_model",
    "format_echo",
    "frames_dot",
    "joint_state_defaults",
    "robot_transforms",
]
