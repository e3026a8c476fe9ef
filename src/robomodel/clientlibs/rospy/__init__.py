"""rospy on robomodel: a rospy node is a robomodel node on the ROS 1 master at
``ROS_MASTER_URI`` (TCPROS and the slave API), so ``rostopic``, ``rosservice``, ``rosnode`` and
``rosparam`` see it and real ROS 1 nodes talk to it.

``import rospy`` gives this package when no real rospy is on the path. What rospy offers and
robomodel does not raises NotImplementedError naming it. ``rospy.robomodel_node()`` (robomodel's
own) gives the robomodel node behind ``init_node``.
"""

from __future__ import annotations

from typing import Any, NoReturn

from robomodel.clientlibs.genpy import Message
from robomodel.clientlibs.rospy.client import (
    delete_param,
    get_node_uri,
    get_param,
    get_param_cached,
    get_param_names,
    get_published_topics,
    has_param,
    init_node,
    myargv,
    search_param,
    set_param,
    spin,
)
from robomodel.clientlibs.rospy.core import (
    DEBUG,
    ERROR,
    FATAL,
    INFO,
    WARN,
    get_caller_id,
    get_name,
    get_namespace,
    is_shutdown,
    logdebug,
    logdebug_once,
    logdebug_throttle,
    logdebug_throttle_identical,
    logerr,
    logerr_once,
    logerr_throttle,
    logerr_throttle_identical,
    logerror,
    logfatal,
    logfatal_once,
    logfatal_throttle,
    logfatal_throttle_identical,
    loginfo,
    loginfo_once,
    loginfo_throttle,
    loginfo_throttle_identical,
    logout,
    logwarn,
    logwarn_once,
    logwarn_throttle,
    logwarn_throttle_identical,
    on_shutdown,
    resolve_name,
    robomodel_node,
    signal_shutdown,
)
from robomodel.clientlibs.rospy.exceptions import (
    ROSException,
    ROSInitException,
    ROSInternalException,
    ROSInterruptException,
    ROSSerializationException,
    ROSTimeMovedBackwardsException,
    ServiceException,
    TransportException,
    TransportInitError,
    TransportTerminated,
)
from robomodel.clientlibs.rospy.rostime import Duration, Time, get_rostime, get_time
from robomodel.clientlibs.rospy.service import Service, ServiceProxy, wait_for_service
from robomodel.clientlibs.rospy.timer import Rate, Timer, TimerEvent, sleep
from robomodel.clientlibs.rospy.topics import (
    Publisher,
    SubscribeListener,
    Subscriber,
    wait_for_message,
)

__all__ = [
    "DEBUG",
    "ERROR",
    "FATAL",
    "INFO",
    "WARN",
    "AnyMsg",
    "Duration",
    "Header",
    "MasterProxy",
    "Message",
    "Publisher",
    "ROSException",
    "ROSInitException",
    "ROSInternalException",
    "ROSInterruptException",
    "ROSSerializationException",
    "ROSTimeMovedBackwardsException",
    "Rate",
    "Service",
    "ServiceException",
    "ServiceProxy",
    "SubscribeListener",
    "Subscriber",
    "Time",
    "Timer",
    "TimerEvent",
    "TransportException",
    "TransportInitError",
    "TransportTerminated",
    "delete_param",
    "get_caller_id",
    "get_master",
    "get_name",
    "get_namespace",
    "get_node_uri",
    "get_param",
    "get_param_cached",
    "get_param_names",
    "get_published_topics",
    "get_ros_root",
    "get_rostime",
    "get_time",
    "has_param",
    "init_node",
    "is_shutdown",
    "logdebug",
    "logdebug_once",
    "logdebug_throttle",
    "logdebug_throttle_identical",
    "logerr",
    "logerr_once",
    "logerr_throttle",
    "logerr_throttle_identical",
    "logerror",
    "logfatal",
    "logfatal_once",
    "logfatal_throttle",
    "logfatal_throttle_identical",
    "loginfo",
    "loginfo_once",
    "loginfo_throttle",
    "loginfo_throttle_identical",
    "logout",
    "logwarn",
    "logwarn_once",
    "logwarn_throttle",
    "logwarn_throttle_identical",
    "myargv",
    "on_shutdown",
    "parse_rosrpc_uri",
    "remap_name",
    "resolve_name",
    "robomodel_node",
    "search_param",
    "set_param",
    "signal_shutdown",
    "sleep",
    "spin",
    "wait_for_message",
    "wait_for_service",
]

# rospy's names that robomodel does not offer: each raises NotImplementedError when used.
UNSUPPORTED = {
    "AnyMsg": "rospy.AnyMsg (subscribing to any type without its class)",
    "MasterProxy": "rospy.MasterProxy (rospy's dict-like parameter server proxy)",
    "get_master": "rospy.get_master() (the master's XML-RPC proxy)",
    "get_ros_root": "rospy.get_ros_root() (there is no ROS installation)",
    "parse_rosrpc_uri": "rospy.parse_rosrpc_uri()",
    "remap_name": "rospy.remap_name() (rospy's name remapping without resolution)",
}


class _Unsupported:
    """A rospy name robomodel does not offer: using it raises NotImplementedError naming it."""

    def __init__(self, what: str) -> None:
        self.what = what

    def __call__(self, *args: Any, **kwargs: Any) -> NoReturn:
        raise NotImplementedError(f"{self.what} is not offered by robomodel's rospy")

    def __repr__(self) -> str:
        return f"<not offered: {self.what}>"


AnyMsg = _Unsupported(UNSUPPORTED["AnyMsg"])
MasterProxy = _Unsupported(UNSUPPORTED["MasterProxy"])
get_master = _Unsupported(UNSUPPORTED["get_master"])
get_ros_root = _Unsupported(UNSUPPORTED["get_ros_root"])
parse_rosrpc_uri = _Unsupported(UNSUPPORTED["parse_rosrpc_uri"])
remap_name = _Unsupported(UNSUPPORTED["remap_name"])


def __getattr__(name: str) -> Any:
    if name == "Header":  # rospy re-exports std_msgs' Header: made on first use
        from std_msgs.msg import Header  # type: ignore[import-not-found]

        globals()["Header"] = Header
        return Header
    raise AttributeError(f"module 'rospy' has no attribute '{name}'")
