"""The rosidl (rclpy) and genpy (rospy) faces of message, service and action types: their
constructors, checks, containers, texts and ROS 1 attributes, as the generated classes of
rosidl_generator_py and genpy have them, and the choice of flavour."""

from __future__ import annotations

import array
import io
import sys
from pathlib import Path

import numpy as np
import pytest

from robomodel.clientlibs import messages
from robomodel.clientlibs.messages import (
    FlavourError,
    action_class,
    flavour,
    flavoured,
    message_class,
    service_class,
)
from robomodel.clientlibs.messages import slot_types as rosidl_definition
from robomodel.runtime.msg import JointState, String, message_to_dict
from robomodel.runtime.msg.cdr import deserialize, serialize
from robomodel.runtime.msg.schema import Action, Message, Service


def test_rosidl_string_is_rclpys() -> None:
    cls = message_class("std_msgs/msg/String", "rosidl")
    msg = cls(data="hi")
    assert repr(msg) == "std_msgs.msg.String(data='hi')"
    assert cls.get_fields_and_field_types() == {"data": "string"}
    assert (rosidl_definition.UnboundedString(),) == cls.SLOT_TYPES
    assert cls.__slots__ == ("_data", "_check_fields")
    assert issubclass(cls, Message) and cls.__typename__ == String.__typename__
    assert cls(data="hi") == msg and cls(data="ho") != msg and String(data="hi") != msg
    with pytest.raises(AssertionError, match="Invalid arguments passed to constructor: bogus"):
        cls(bogus=1)
    with pytest.raises(AssertionError, match="The 'data' field must be of type 'str'"):
        msg.data = 3
    with pytest.raises(TypeError):
        cls("positional")  # rosidl's constructor takes keywords only


def test_rosidl_containers_checks_and_repr() -> None:
    cls = message_class("sensor_msgs/msg/JointState", "rosidl")
    msg = cls(name=["a", "b"], position=[1.0, 2.0])
    assert isinstance(msg.position, array.array) and msg.position.typecode == "d"
    assert repr(msg).endswith("name=['a', 'b'], position=[1.0, 2.0], velocity=[], effort=[])")
    assert type(msg.header).__typename__ == "std_msgs/msg/Header"
    assert cls.get_fields_and_field_types()["position"] == "sequence<double>"
    assert cls.get_fields_and_field_types()["header"] == "std_msgs/Header"
    with pytest.raises(AssertionError, match="each value of type 'float'"):
        msg.position = [1, 2]
    with pytest.raises(AssertionError, match="must be a sub message of type 'Header'"):
        msg.header = String()
    imu = message_class("sensor_msgs/msg/Imu", "rosidl")()
    assert isinstance(imu.orientation_covariance, np.ndarray)
    assert imu.orientation_covariance.dtype == np.float64 and imu.orientation_covariance.shape == (
        9,
    )
    with pytest.raises(AssertionError, match="must have a size of 9"):
        imu.orientation_covariance = np.zeros(3)
    image = message_class("sensor_msgs/msg/Image", "rosidl")(data=b"\x01\x02")
    assert image.data == array.array("B", [1, 2])
    unchecked = message_class("std_msgs/msg/Int8", "rosidl")(check_fields=False)
    unchecked.data = 1000  # checks off, as with ROS_PYTHON_CHECK_FIELDS unset in Jazzy
    with pytest.raises(AssertionError, match=r"integer in \[-128, 127\]"):
        message_class("std_msgs/msg/Int8", "rosidl")(data=1000)


def test_rosidl_octets_are_bytes_and_encode_as_robomodels() -> None:
    byte = message_class("std_msgs/msg/Byte", "rosidl")
    assert byte().data == b"\x00"
    assert serialize(byte(data=b"\x07")) == serialize(get_own("std_msgs/msg/Byte")(data=7))
    assert deserialize(serialize(byte(data=b"\x07")), byte).data == b"\x07"
    many = message_class("std_msgs/msg/ByteMultiArray", "rosidl")(data=[b"\x01", b"\x02"])
    back = deserialize(serialize(many), type(many))
    assert back.data == [b"\x01", b"\x02"]


def get_own(name: str) -> type[Message]:
    from robomodel.runtime.msg import get_message_type

    return get_message_type(name)


def test_decoding_gives_the_flavour_with_its_containers() -> None:
    ours = JointState(name=["j"], position=[0.5], velocity=[1.5], effort=[])
    data = serialize(ours)
    rosidl = deserialize(data, flavoured(JointState, "rosidl"))
    assert isinstance(rosidl.velocity, array.array) and list(rosidl.velocity) == [1.5]
    assert type(rosidl.header) is flavoured(get_own("std_msgs/msg/Header"), "rosidl")
    genpy = deserialize(data, flavoured(JointState, "genpy"))
    assert genpy.position == [0.5] and genpy.header.stamp.secs == 0
    assert serialize(rosidl) == serialize(genpy) == data
    assert message_to_dict(rosidl)["name"] == ["j"]


def test_constants_are_class_attributes() -> None:
    cls = message_class("visualization_msgs/msg/Marker", "rosidl")
    assert cls.ARROW == 0 and cls.DELETEALL == 3
    assert message_class("visualization_msgs/msg/Marker", "genpy").DELETEALL == 3


def test_rosidl_services_and_actions() -> None:
    service = service_class("std_srvs/srv/SetBool", "rosidl")
    assert issubclass(service, Service)
    assert repr(service.Request(data=True)) == "std_srvs.srv.SetBool_Request(data=True)"
    assert service.Response().message == ""
    assert service.Event.get_fields_and_field_types()["request"] == (
        "sequence<std_srvs/SetBool_Request, 1>"
    )
    with pytest.raises(NotImplementedError, match="Service classes can not be instantiated"):
        service()
    action = action_class("control_msgs/action/FollowJointTrajectory", "rosidl")
    assert issubclass(action, Action)
    goal = action.Goal()
    assert repr(goal).startswith("control_msgs.action.FollowJointTrajectory_Goal(trajectory=")
    impl = action.Impl
    request = impl.SendGoalService.Request(goal=goal)
    assert request.goal_id.uuid.shape == (16,)
    assert impl.GetResultService.Response().result == action.Result()
    assert type(impl.FeedbackMessage().feedback) is action.Feedback
    assert impl.CancelGoalService.__typename__ == "action_msgs/srv/CancelGoal"
    assert impl.GoalStatusMessage.__typename__ == "action_msgs/msg/GoalStatusArray"
    assert action.SendGoal is impl.SendGoalService


def test_genpy_message_is_rospys() -> None:
    cls = message_class("std_msgs/msg/String", "genpy")
    assert cls._type == "std_msgs/String"
    assert cls._md5sum == "992ce8a1687cec8c8bd883ec73ca41d1"  # genmsg's, as rospy sends it
    assert cls._full_text.strip() == "string data"
    assert cls.__slots__ == ("data",) and cls._slot_types == ["string"]
    assert cls("a") == cls(data="a") and str(cls("a")) == 'data: "a"'
    assert cls().data == "" and cls(None).data == ""
    with pytest.raises(TypeError, match="args OR keywords"):
        cls("a", data="b")
    with pytest.raises(TypeError, match="Invalid number of arguments"):
        cls("a", "b")
    with pytest.raises(AttributeError, match="bogus is not an attribute of String"):
        cls(bogus=1)
    buff = io.BytesIO()
    cls("hello").serialize(buff)
    assert buff.getvalue() == b"\x05\x00\x00\x00hello"
    assert cls().deserialize(buff.getvalue()).data == "hello"


def test_genpy_header_time_and_arrays() -> None:
    header = message_class("std_msgs/msg/Header", "genpy")
    assert header.__slots__ == ("seq", "stamp", "frame_id")
    assert header._slot_types == ["uint32", "time", "string"]
    stamp = type(header().stamp)(5, 1_500_000_000)
    assert (stamp.secs, stamp.nsecs) == (6, 500_000_000) and stamp.to_sec() == 6.5
    assert (stamp - type(stamp)(1, 0)).to_sec() == 5.5
    joint_state = message_class("sensor_msgs/msg/JointState", "genpy")
    assert joint_state._has_header and not message_class("std_msgs/msg/String", "genpy")._has_header
    msg = joint_state(header(7, stamp, "base"), ["j"], [1.0], [], [])
    assert str(msg).splitlines()[:5] == [
        "header: ",
        "  seq: 7",
        "  stamp: ",
        "    secs: 6",
        "    nsecs: 500000000",
    ]
    image = message_class("sensor_msgs/msg/Image", "genpy")()
    assert image.data == b"" and image._slot_types[-1] == "uint8[]"
    buff = io.BytesIO()
    msg.serialize(buff)
    back = joint_state().deserialize_numpy(buff.getvalue(), np)
    assert isinstance(back.position, np.ndarray) and back.header.frame_id == "base"


def test_genpy_services() -> None:
    service = service_class("std_srvs/srv/SetBool", "genpy")
    assert service._type == "std_srvs/SetBool"
    assert service._md5sum == "09fb03525b03e7ea1fd3992bafd87e16"
    assert service._request_class is service.Request
    assert service.Request.__name__ == "SetBoolRequest"
    assert service.Request._type == "std_srvs/SetBoolRequest"
    assert service._response_class(True, "done").message == "done"


def test_flavour_choice(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.delenv("ROBOMODEL_MESSAGE_FLAVOUR", raising=False)
    for name in ("rospy", "rclpy", "robomodel.clientlibs.rospy", "robomodel.clientlibs.rclpy"):
        monkeypatch.delitem(sys.modules, name, raising=False)
    script = tmp_path / "node.py"
    script.write_text("import os\nfrom std_msgs.msg import String\nimport rospy\n")
    main = type(sys)("__main__")
    main.__file__ = str(script)
    monkeypatch.setitem(sys.modules, "__main__", main)
    assert flavour() == "genpy"  # the script's imports
    script.write_text("import rclpy\n")
    assert flavour() == "rosidl"
    monkeypatch.setitem(sys.modules, "rospy", type(sys)("rospy"))
    assert flavour() == "genpy"  # rospy imported
    monkeypatch.setenv("ROBOMODEL_MESSAGE_FLAVOUR", "rosidl")
    assert flavour() == "rosidl"  # the environment first
    monkeypatch.setenv("ROBOMODEL_MESSAGE_FLAVOUR", "cpp")
    with pytest.raises(FlavourError, match="flavours are: rosidl, genpy"):
        flavour()
    monkeypatch.delenv("ROBOMODEL_MESSAGE_FLAVOUR")
    monkeypatch.delitem(sys.modules, "rospy")
    script.write_text("print('no client library')\n")
    assert flavour() == "rosidl"


def test_one_class_per_flavour_and_type() -> None:
    rosidl = flavoured(JointState, "rosidl")
    assert flavoured(JointState, "rosidl") is rosidl
    assert flavoured(rosidl, "genpy") is flavoured(JointState, "genpy")
    assert messages.message_class("sensor_msgs/JointState", "rosidl") is rosidl


def test_copies_and_pickles_keep_the_flavour() -> None:
    import copy
    import pickle

    for name in ("rosidl", "genpy"):
        cls = message_class("sensor_msgs/msg/JointState", name)
        msg = cls(name=["a"], position=[1.0])
        msg.header.frame_id = "base"
        for again in (copy.deepcopy(msg), pickle.loads(pickle.dumps(msg))):
            assert type(again) is cls and again == msg and again is not msg


def test_package_path_set_at_run_time(tmp_path: Path) -> None:
    """``robomodel run --package-path`` configures the resolver: the finder and the
    interface modules see the package from then on."""
    from robomodel.clientlibs import interfaces
    from robomodel.runtime.msg import _resolver

    package = tmp_path / "late_interfaces"
    (package / "msg").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>late_interfaces</name></package>")
    (package / "msg" / "Late.msg").write_text("string note\n")
    with pytest.raises(ModuleNotFoundError, match="No module named 'late_interfaces'"):
        interfaces.find_spec("late_interfaces.msg")  # close to rcl_interfaces: it says so
    before = _resolver.package_paths()
    _resolver.configure(package_paths=(*before, tmp_path))
    try:
        spec = interfaces.find_spec("late_interfaces.msg")
        assert spec is not None and spec.loader is not None
        module = spec.loader.create_module(spec)
        assert module is not None and module.__all__ == ["Late"]
        assert module.Late(note="x").note == "x"
    finally:
        _resolver.configure(package_paths=before)
    with pytest.raises(ModuleNotFoundError):
        interfaces.find_spec("late_interfaces.msg")


def test_flavours_share_the_type_hash_and_md5sum() -> None:
    from robomodel.runtime.msg.typehash import type_hash
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type

    for name in ("rosidl", "genpy"):
        face = flavoured(JointState, name)
        assert type_hash(face) == type_hash(JointState)
        assert ros1_type(face).md5sum == ros1_type(JointState).md5sum
        assert ros1_type(face).cls is face
