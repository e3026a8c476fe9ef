"""ROS 2 message types as Python dataclasses, their CDR encoding and YAML conversion.

The types of ``builtin_interfaces``, ``std_msgs``, ``geometry_msgs`` and ``rosgraph_msgs`` are
imported with the package; the others named here are imported when first used
(``from robomodel.runtime.msg import JointState``), so that a process that never uses
control_msgs does not pay for it.
"""

from robomodel._lazy import lazy_exports
from robomodel.runtime.msg import _resolver as _resolver  # installs the fallback for unknown types
from robomodel.runtime.msg.cdr import CDRError, deserialize, serialize
from robomodel.runtime.msg.schema import (
    Array,
    Message,
    MessageTypeError,
    Seq,
    canonical_type_name,
    get_message_type,
    message_type_names,
)
from robomodel.runtime.msg.types.builtin_interfaces import Duration, Time
from robomodel.runtime.msg.types.geometry_msgs import (
    Point,
    Pose,
    PoseWithCovariance,
    Quaternion,
    Transform,
    TransformStamped,
    Twist,
    TwistStamped,
    TwistWithCovariance,
    Vector3,
)
from robomodel.runtime.msg.types.rosgraph_msgs import Clock  # every node's /clock
from robomodel.runtime.msg.types.std_msgs import (
    Bool,
    Empty,
    Float64,
    Float64MultiArray,
    Header,
    Int32,
    MultiArrayDimension,
    MultiArrayLayout,
    String,
)
from robomodel.runtime.msg.yaml_io import (
    message_from_dict,
    message_from_yaml,
    message_to_dict,
    message_to_yaml,
)

TYPE_CHECKING = False
if TYPE_CHECKING:
    from robomodel.runtime.msg.types.control_msgs import (
        DynamicJointState,
        InterfaceValue,
        JointControllerState,
        JointTrajectoryControllerState,
    )
    from robomodel.runtime.msg.types.nav_msgs import Odometry
    from robomodel.runtime.msg.types.sensor_msgs import Imu, JointState, LaserScan
    from robomodel.runtime.msg.types.tf2_msgs import TFMessage
    from robomodel.runtime.msg.types.trajectory_msgs import (
        JointTrajectory,
        JointTrajectoryPoint,
        MultiDOFJointTrajectoryPoint,
    )

# The classes above, by the module that defines them, imported on first use.
_MODULE_OF = {
    name: f"{__name__}.types.{package}"
    for package, names in {
        "control_msgs": (
            "DynamicJointState",
            "InterfaceValue",
            "JointControllerState",
            "JointTrajectoryControllerState",
        ),
        "nav_msgs": ("Odometry",),
        "sensor_msgs": ("Imu", "JointState", "LaserScan"),
        "tf2_msgs": ("TFMessage",),
        "trajectory_msgs": (
            "JointTrajectory",
            "JointTrajectoryPoint",
            "MultiDOFJointTrajectoryPoint",
        ),
    }.items()
    for name in names
}

__all__ = [
    "Array",
    "Bool",
    "CDRError",
    "Clock",
    "Duration",
    "DynamicJointState",
    "Empty",
    "Float64",
    "Float64MultiArray",
    "Header",
    "Imu",
    "Int32",
    "InterfaceValue",
    "JointControllerState",
    "JointState",
    "JointTrajectory",
    "JointTrajectoryControllerState",
    "JointTrajectoryPoint",
    "LaserScan",
    "Message",
    "MessageTypeError",
    "MultiArrayDimension",
    "MultiArrayLayout",
    "MultiDOFJointTrajectoryPoint",
    "Odometry",
    "Point",
    "Pose",
    "PoseWithCovariance",
    "Quaternion",
    "Seq",
    "String",
    "TFMessage",
    "Time",
    "Transform",
    "TransformStamped",
    "Twist",
    "TwistStamped",
    "TwistWithCovariance",
    "Vector3",
    "canonical_type_name",
    "deserialize",
    "get_message_type",
    "message_from_dict",
    "message_from_yaml",
    "message_to_dict",
    "message_to_yaml",
    "message_type_names",
    "serialize",
]

__getattr__, __dir__ = lazy_exports(__name__, _MODULE_OF, globals(), __all__)
