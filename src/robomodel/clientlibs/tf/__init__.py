"""ROS 1's ``tf`` on robomodel: ``TransformListener`` (``lookupTransform``,
``waitForTransform``, ``canTransform``, ``transformPoint``, ...), ``TransformBroadcaster``
and ``tf.transformations``, over the rospy node of this process (``/tf``, ``/tf_static``).
"""

from robomodel.clientlibs.tf import transformations
from robomodel.clientlibs.tf._broadcaster import TransformBroadcaster
from robomodel.clientlibs.tf._listener import (
    ConnectivityException,
    Exception,
    ExtrapolationException,
    LookupException,
    Transformer,
    TransformerROS,
    TransformListener,
)

__all__ = [
    "ConnectivityException",
    "Exception",
    "ExtrapolationException",
    "LookupException",
    "TransformBroadcaster",
    "TransformListener",
    "Transformer",
    "TransformerROS",
    "transformations",
]
