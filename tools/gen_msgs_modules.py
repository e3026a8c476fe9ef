"""What tools/gen_msgs.py generates: robomodel's typed message modules, one per ROS package
(runtime/msg/types/<package>.py), the types each holds, and the few things a definition does
not say (defaults, helpers)."""

from __future__ import annotations

# ROS package -> (docstring's first line, the types of it robomodel has classes of: pkg/msg/X,
# pkg/srv/X, pkg/action/X)
MODULES: dict[str, tuple[str, tuple[str, ...]]] = {
    "builtin_interfaces": (
        "builtin_interfaces: Time and Duration.",
        ("builtin_interfaces/msg/Time", "builtin_interfaces/msg/Duration"),
    ),
    "std_msgs": (
        "std_msgs: Header, String, Float64, Float64MultiArray (with its layout), Bool, Int32, "
        "Empty.",
        tuple(
            f"std_msgs/msg/{n}"
            for n in (
                "Header",
                "String",
                "Float64",
                "Bool",
                "Int32",
                "Empty",
                "MultiArrayDimension",
                "MultiArrayLayout",
                "Float64MultiArray",
            )
        ),
    ),
    "geometry_msgs": (
        "geometry_msgs: vectors, quaternions, poses, transforms, twists and wrenches.",
        tuple(
            f"geometry_msgs/msg/{n}"
            for n in (
                "Vector3",
                "Point",
                "Quaternion",
                "Pose",
                "Transform",
                "TransformStamped",
                "Twist",
                "TwistStamped",
                "Wrench",
                "PoseWithCovariance",
                "TwistWithCovariance",
            )
        ),
    ),
    "sensor_msgs": (
        "sensor_msgs: JointState, LaserScan, Imu.",
        ("sensor_msgs/msg/JointState", "sensor_msgs/msg/LaserScan", "sensor_msgs/msg/Imu"),
    ),
    "trajectory_msgs": (
        "trajectory_msgs: JointTrajectory, JointTrajectoryPoint and their multi-DOF counterparts.",
        tuple(
            f"trajectory_msgs/msg/{n}"
            for n in (
                "JointTrajectoryPoint",
                "JointTrajectory",
                "MultiDOFJointTrajectoryPoint",
                "MultiDOFJointTrajectory",
            )
        ),
    ),
    "nav_msgs": ("nav_msgs: Odometry.", ("nav_msgs/msg/Odometry",)),
    "tf2_msgs": (
        "tf2_msgs: TFMessage, the message of /tf and /tf_static.",
        ("tf2_msgs/msg/TFMessage",),
    ),
    "rosgraph_msgs": (
        "rosgraph_msgs: Clock (/clock) and ROS 1's Log (/rosout).",
        ("rosgraph_msgs/msg/Clock", "rosgraph_msgs/msg/Log"),
    ),
    "lifecycle_msgs": (
        "lifecycle_msgs: State, the state of a managed node or hardware component.",
        ("lifecycle_msgs/msg/State",),
    ),
    "service_msgs": (
        "service_msgs: ServiceEventInfo, the header of every service's ``_Event`` message.",
        ("service_msgs/msg/ServiceEventInfo",),
    ),
    "unique_identifier_msgs": (
        "unique_identifier_msgs: UUID, the id of an action's goal.",
        ("unique_identifier_msgs/msg/UUID",),
    ),
    "action_msgs": (
        "action_msgs: goal ids, goal status and the cancel service every ROS 2 action server "
        "offers.",
        (
            "action_msgs/msg/GoalInfo",
            "action_msgs/msg/GoalStatus",
            "action_msgs/msg/GoalStatusArray",
            "action_msgs/srv/CancelGoal",
        ),
    ),
    "rcl_interfaces": (
        "rcl_interfaces: parameter values, descriptors and events, the parameter services and "
        "/rosout's Log.",
        (
            *(
                f"rcl_interfaces/msg/{n}"
                for n in (
                    "ParameterValue",
                    "Parameter",
                    "FloatingPointRange",
                    "IntegerRange",
                    "ParameterType",
                    "ParameterDescriptor",
                    "SetParametersResult",
                    "ListParametersResult",
                    "ParameterEvent",
                    "Log",
                )
            ),
            *(
                f"rcl_interfaces/srv/{n}"
                for n in (
                    "GetParameters",
                    "SetParameters",
                    "SetParametersAtomically",
                    "ListParameters",
                    "DescribeParameters",
                    "GetParameterTypes",
                )
            ),
        ),
    ),
    "std_srvs": (
        "std_srvs: Empty, Trigger and SetBool.",
        ("std_srvs/srv/Empty", "std_srvs/srv/Trigger", "std_srvs/srv/SetBool"),
    ),
    "roscpp": (
        "roscpp (ROS 1): the logger services every roscpp and rospy node offers, GetLoggers and "
        "SetLoggerLevel, with their Logger.",
        ("roscpp/msg/Logger", "roscpp/srv/GetLoggers", "roscpp/srv/SetLoggerLevel"),
    ),
    "control_msgs": (
        "control_msgs: controller states, QueryTrajectoryState and FollowJointTrajectory (the "
        "joint_trajectory_controller's ``~/query_state`` and ``~/follow_joint_trajectory``).",
        (
            *(
                f"control_msgs/msg/{n}"
                for n in (
                    "InterfaceValue",
                    "DynamicJointState",
                    "JointControllerState",
                    "JointTrajectoryControllerState",
                    "JointTolerance",
                    "JointComponentTolerance",
                )
            ),
            "control_msgs/srv/QueryTrajectoryState",
            "control_msgs/action/FollowJointTrajectory",
        ),
    ),
    "controller_manager_msgs": (
        "controller_manager_msgs (ros2_control): the controller manager's controller and "
        "hardware component services and their messages.",
        (
            *(
                f"controller_manager_msgs/msg/{n}"
                for n in (
                    "ChainConnection",
                    "ControllerState",
                    "NamedLifecycleState",
                    "ControllerManagerActivity",
                    "HardwareInterface",
                    "HardwareComponentState",
                )
            ),
            *(
                f"controller_manager_msgs/srv/{n}"
                for n in (
                    "ListControllers",
                    "ListControllerTypes",
                    "LoadController",
                    "ConfigureController",
                    "CleanupController",
                    "SwitchController",
                    "UnloadController",
                    "ReloadControllerLibraries",
                    "ListHardwareComponents",
                    "ListHardwareInterfaces",
                    "SetHardwareComponentState",
                )
            ),
        ),
    ),
    "gazebo_msgs": (
        "gazebo_msgs (gazebo_ros_pkgs): the simulator's spawn, delete, state, world and wrench "
        "services, and model and link states and properties (Gazebo's scoped link names, "
        "``model::link``).",
        (
            "gazebo_msgs/msg/ModelState",
            "gazebo_msgs/msg/EntityState",
            "gazebo_msgs/msg/LinkState",
            "gazebo_msgs/msg/ModelStates",
            "gazebo_msgs/msg/LinkStates",
            *(
                f"gazebo_msgs/srv/{n}"
                for n in (
                    "SpawnModel",
                    "SpawnEntity",
                    "DeleteModel",
                    "DeleteEntity",
                    "SetModelState",
                    "GetModelState",
                    "SetEntityState",
                    "GetEntityState",
                    "SetModelConfiguration",
                    "GetWorldProperties",
                    "GetModelList",
                    "ApplyBodyWrench",
                    "GetLinkState",
                    "SetLinkState",
                    "GetModelProperties",
                )
            ),
        ),
    ),
    "robomodel_interfaces": (
        "robomodel_interfaces: robomodel's own service types, for what ROS has no type for "
        "(MasterCall: a call of the ROS 1 parameter server robomodel launch hosts on the Zenoh "
        "bus, on /_robomodel_params/call).",
        ("robomodel_interfaces/srv/MasterCall",),
    ),
    "type_description_interfaces": (
        "type_description_interfaces (REP-2011): type descriptions, and GetTypeDescription, "
        "which every node on a ROS 2 bus answers.",
        (
            *(
                f"type_description_interfaces/msg/{n}"
                for n in (
                    "FieldType",
                    "Field",
                    "IndividualTypeDescription",
                    "TypeDescription",
                    "TypeSource",
                    "KeyValue",
                )
            ),
            "type_description_interfaces/srv/GetTypeDescription",
        ),
    ),
    "ros_gz_interfaces": (
        "ros_gz_interfaces (ros_gz): ControlWorld, Gazebo Sim's pause / step / reset request.",
        (
            "ros_gz_interfaces/msg/WorldReset",
            "ros_gz_interfaces/msg/WorldControl",
            "ros_gz_interfaces/srv/ControlWorld",
        ),
    ),
}

# Defaults of the definitions (other than zero), which rosbags does not keep.
DEFAULTS: dict[tuple[str, str], object] = {
    ("geometry_msgs/msg/Quaternion", "w"): 1.0,
    # robomodel's own MasterCall.srv (``string arguments "{}"``, ``string result "null"``)
    ("robomodel_interfaces/srv/MasterCall_Request", "arguments"): "{}",
    ("robomodel_interfaces/srv/MasterCall_Response", "result"): "null",
}
# Helpers (robomodel.runtime.msg._methods) mixed into a generated class.
MIXINS = {
    "builtin_interfaces/msg/Time": "TimeMethods",
    "builtin_interfaces/msg/Duration": "DurationMethods",
    "unique_identifier_msgs/msg/UUID": "UUIDMethods",
}
# Types read from a ROS 1 store (they exist in ROS 1 only).
ROS1_ONLY = {"rosgraph_msgs/msg/Log"}

# Earlier layouts of types (runtime/msg/layouts/<package>.py, one module per ROS package): the
# class name, the release folder under runtime/msg/interface_versions/ and the type. Their
# classes are named as the real type but not registered, so the registry keeps the current layout.
VARIANTS: dict[str, tuple[str, tuple[tuple[str, str, str], ...]]] = {
    "controller_manager_msgs": (
        "controller_manager_msgs' ControllerState in the layouts of earlier Jazzy ros2_control "
        "releases (4.0-4.12 and 4.13-4.27), for runtime/msg/service_variants.py.",
        (
            (
                "ControllerState_4_0",
                "ros2_control-4.12.0",
                "controller_manager_msgs/msg/ControllerState",
            ),
            (
                "ControllerState_4_13",
                "ros2_control-4.13.0",
                "controller_manager_msgs/msg/ControllerState",
            ),
        ),
    ),
}
