"""A class built from a definition before the type sources changed is still its type.

``configure`` (``--package-path``, ``--distro``) forgets the classes built from definitions, so
code that held ``get_message_type("sensor_msgs/msg/Image")`` from before has a different class
object than code asking afterwards. CI saw the in-process bus refuse to deliver between the two
("published as sensor_msgs/msg/Image but subscribed as sensor_msgs/msg/Image") and ROS 1 refuse
the older class; both now compare the type's name and hash.
"""

from __future__ import annotations

from typing import Any

import pytest

from robomodel.runtime import Context
from robomodel.runtime.msg import _resolver, get_message_type
from robomodel.runtime.msg.typehash import same_type

IMAGE = "sensor_msgs/msg/Image"


def _rebuilt() -> tuple[Any, Any]:
    before = get_message_type(IMAGE)
    _resolver.configure()  # what a CLI's --package-path/--distro does
    after = get_message_type(IMAGE)
    return before, after


def test_a_rebuilt_class_is_the_same_type_and_a_different_one_is_not() -> None:
    before, after = _rebuilt()
    assert before is not after  # the premise: configure rebuilt it
    assert same_type(before, after)
    assert not same_type(before, get_message_type("sensor_msgs/msg/CompressedImage"))


def test_the_inproc_bus_delivers_between_the_old_and_the_new_class() -> None:
    before, after = _rebuilt()
    got: list[Any] = []
    with Context("inproc") as ctx:
        node = ctx.create_node("n")
        node.create_subscription(after, "/img", got.append, 10)
        node.create_publisher(before, "/img", 10).publish(before(width=2, height=1))
        ctx.spin_once(0.0)
    assert [(m.width, m.height) for m in got] == [(2, 1)]


def test_ros1_takes_the_old_class() -> None:
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type

    before, after = _rebuilt()
    assert ros1_type(before).name == ros1_type(after).name == "sensor_msgs/Image"


def test_configure_with_the_same_settings_keeps_the_classes() -> None:
    _resolver.configure(package_paths=())
    first = get_message_type(IMAGE)
    _resolver.configure(package_paths=())
    assert get_message_type(IMAGE) is first


# -- the registry and the classes made at run time (schema, _from_definition) --------------


def test_type_names_in_either_form_are_one_key() -> None:
    from robomodel.runtime.msg.schema import canonical_service_name, canonical_type_name

    assert canonical_type_name(" /std_msgs/Float64/ ") == "std_msgs/msg/Float64"
    assert canonical_type_name("std_msgs/msg/Float64") == "std_msgs/msg/Float64"
    assert canonical_type_name("Float64") == "Float64"
    assert canonical_type_name("X_msgs/PoseX") == "X_msgs/msg/PoseX"  # only "/" is stripped
    assert canonical_service_name("X_srvs/SetX") == "X_srvs/srv/SetX"
    assert canonical_service_name(" /std_srvs/Empty/ ") == "std_srvs/srv/Empty"
    assert canonical_service_name("std_srvs/srv/Empty") == "std_srvs/srv/Empty"
    assert get_message_type("std_msgs/Float64") is get_message_type("/std_msgs/msg/Float64")


def test_services_by_either_name_and_the_lists_of_names() -> None:
    from robomodel.runtime.msg.schema import (
        get_service_type,
        message_type_names,
        service_type_names,
    )

    srv = get_service_type("std_srvs/SetBool")
    assert srv is get_service_type("std_srvs/srv/SetBool")
    assert srv.__typename__ == "std_srvs/srv/SetBool"
    names = service_type_names()
    assert "std_srvs/srv/SetBool" in names and list(names) == sorted(names)
    messages = message_type_names()
    assert "std_msgs/msg/Float64" in messages and list(messages) == sorted(messages)
    # an unknown one goes to the resolver, which names it as the user wrote it
    from robomodel.runtime.msg import MessageTypeError

    with pytest.raises(MessageTypeError, match="unknown service type 'no_pkg/Nothing'"):
        get_service_type("no_pkg/Nothing")
    with pytest.raises(MessageTypeError, match="'no_pkg/Nothing'"):
        get_message_type("no_pkg/Nothing")


def test_without_a_resolver_an_unknown_type_is_one_line() -> None:
    from robomodel.runtime.msg import MessageTypeError, schema

    saved = list(schema._RESOLVER)
    schema._RESOLVER.clear()
    try:
        for look_up in (schema.get_message_type, schema.get_service_type):
            with pytest.raises(MessageTypeError) as refused:
                look_up("no_such_pkg/Thing")
            assert str(refused.value) == (
                "no definition resolver installed (import robomodel.runtime.msg)"
            )
        schema.install_definition_resolver(saved[0])
        schema.install_definition_resolver(saved[0])
        assert saved == schema._RESOLVER  # installed once, not appended
    finally:
        schema._RESOLVER[:] = saved


def test_own_classes_register_when_defined_and_derived_ones_when_asked() -> None:
    from robomodel.runtime.msg import schema
    from robomodel.runtime.msg._from_definition import build_service_class, make_message_class

    class Own(schema.Message):
        __typename__ = "test_pkg/msg/Own"

    class Derived(Own):  # inherits the name: not entered again
        pass

    class OwnService(schema.Service):
        __typename__ = "test_pkg/srv/OwnService"

    try:
        assert schema._REGISTRY["test_pkg/msg/Own"] is Own
        assert schema._SERVICES["test_pkg/srv/OwnService"] is OwnService
        made = make_message_class("test_pkg/msg/Made", (("x", "float64"),))
        assert "test_pkg/msg/Made" not in schema._REGISTRY  # the caller decides
        schema.register(made)
        assert schema.get_message_type("test_pkg/Made") is made
        service = build_service_class("test_pkg/srv/Made", made, Own)
        schema.register(service)
        assert schema.get_service_type("test_pkg/Made") is service
        assert "test_pkg/srv/Made" not in schema._REGISTRY
    finally:
        for key in ("test_pkg/msg/Own", "test_pkg/msg/Made"):
            schema._REGISTRY.pop(key, None)
        for key in ("test_pkg/srv/OwnService", "test_pkg/srv/Made"):
            schema._SERVICES.pop(key, None)
    assert Derived.__typename__ == "test_pkg/msg/Own"


def test_defaults_are_fresh_values_of_each_kind() -> None:
    from robomodel.runtime.msg.schema import Array, Seq, default_for

    point = get_message_type("geometry_msgs/msg/Point")
    assert default_for("float64") == 0.0 and default_for("string") == ""
    assert default_for(Array("uint8", 3)) == b"\x00\x00\x00"
    assert default_for(Seq("uint8")) == b""
    assert default_for(Array("float64", 2)) == [0.0, 0.0]
    points = default_for(Array(point, 2))
    assert points == [point(), point()] and points[0] is not points[1]
    assert default_for(Seq("float64")) == [] and default_for(Seq("float64")) is not default_for(
        Seq("float64")
    )
    assert default_for(point) == point() and default_for(point) is not default_for(point)


def test_a_class_made_from_fields_and_constants() -> None:
    from robomodel.runtime.msg import schema
    from robomodel.runtime.msg._from_definition import build_service_class, make_message_class

    point = get_message_type("geometry_msgs/msg/Point")
    cls = make_message_class(
        "test_pkg/msg/Sample",
        (
            ("name", "string<=5"),
            ("count", "int32"),
            ("data", schema.Seq("uint8")),
            ("values", schema.Array("float64", 2)),
            ("where", point),
        ),
        (("LIMIT", "int32", 7), ("LABEL", "string", "x")),
        module="test_module",
    )
    assert cls.__name__ == "Sample" and cls.__module__ == "test_module"
    assert cls.__typename__ == "test_pkg/msg/Sample"
    assert (cls.LIMIT, cls.LABEL) == (7, "x")  # type: ignore[attr-defined]
    assert cls.__constants__ == (("LIMIT", "int32", 7), ("LABEL", "string", "x"))
    assert [n for n, _ in cls.__fields__] == ["name", "count", "data", "values", "where"]
    a, b = cls(), cls()
    assert (a.name, a.count, a.data, a.values, a.where) == ("", 0, b"", [0.0, 0.0], point())  # type: ignore[attr-defined]
    assert a.where is not b.where and a.values is not b.values  # type: ignore[attr-defined]
    assert not hasattr(a, "__dict__")  # slotted
    annotations = cls.__annotations__
    assert annotations["name"] is str and annotations["count"] is int
    assert annotations["data"] is bytes and annotations["where"] is point
    given = cls(name="abc", count=3)
    assert (given.name, given.count) == ("abc", 3)  # type: ignore[attr-defined]
    assert repr(given).startswith("Sample(name='abc', count=3")
    service = build_service_class("test_pkg/srv/Sample", cls, point, module="test_module")
    assert service.__name__ == "Sample" and service.__module__ == "test_module"
    assert (service.Request, service.Response) == (cls, point)
    assert service.__typename__ == "test_pkg/srv/Sample"
    assert issubclass(service, schema.Service)


def test_a_flavoured_class_is_made_by_its_flavour() -> None:
    from robomodel.runtime.msg import schema
    from robomodel.runtime.msg._from_definition import make_message_class

    class Base:
        __slots__ = ()

    finished: list[type] = []

    class Flavour:
        def class_name(self, name: str) -> str:
            return "Flavoured" + name.rsplit("/", 1)[-1]

        def class_body(self, name: str, specs: Any, constants: Any) -> Any:
            return (Base,), {"__slots__": ("x",), "made_for": (name, specs, constants)}

        def finish(self, cls: type) -> None:
            finished.append(cls)

    defaults = {"x": 1.0}
    cls = make_message_class(
        "test_pkg/msg/F", (("x", "float64"),), (("K", "int8", 1),), flavour=Flavour(),
        defaults=defaults,
    )  # fmt: skip
    assert cls.__name__ == "FlavouredF" and cls.__mro__[1:3] == (Base, schema.Message)
    assert cls.made_for == ("test_pkg/msg/F", (("x", "float64"),), (("K", "int8", 1),))  # type: ignore[attr-defined]
    assert cls.__field_defaults__ == {"x": 1.0} and cls.__field_defaults__ is not defaults  # type: ignore[attr-defined]
    assert cls.K == 1 and cls.__typename__ == "test_pkg/msg/F"  # type: ignore[attr-defined]
    assert finished == [cls]
    assert make_message_class("test_pkg/msg/G", (), flavour=Flavour()).__field_defaults__ == {}  # type: ignore[attr-defined]


def test_a_class_built_from_a_definition_keeps_its_constants_as_text_names() -> None:
    from robomodel.runtime.msg._from_definition import build_message_class
    from robomodel.runtime.msg.definition import parse_message

    text = "int8 A=1\nstring B=hi\nint8 value\n"
    definition = parse_message(text, "pkg/msg/C", where="test")["pkg/msg/C"]
    cls = build_message_class("pkg/msg/C", definition, get_message_type)
    assert cls.__constants__ == (("A", "int8", 1), ("B", "string", "hi"))
    assert [n for n, _ in cls.__fields__] == ["value"]
    assert cls.__typename__ == "pkg/msg/C" and cls.__name__ == "C"


def test_a_package_s_module_is_imported_when_one_of_its_types_is_asked_for(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    import sys

    import robomodel.runtime.msg.types as types_package
    from robomodel.runtime.msg import schema

    module = "robomodel.runtime.msg.types.gazebo_msgs"
    # the package's attribute and sys.modules get the module imported anew: both are restored
    before = getattr(types_package, "gazebo_msgs", None)
    monkeypatch.setattr(types_package, "gazebo_msgs", before, raising=False)
    saved = dict(schema._REGISTRY)
    try:
        monkeypatch.delitem(sys.modules, module, raising=False)
        schema.import_package("not a package/msg/X")  # not a name: nothing to import
        schema.import_package("no_such_pkg/msg/X")  # robomodel has no module of it
        assert module not in sys.modules
        schema.import_package("gazebo_msgs/msg/ModelStates")
        assert module in sys.modules
        assert schema._REGISTRY["gazebo_msgs/msg/ModelStates"] is sys.modules[module].ModelStates
    finally:
        schema._REGISTRY.clear()
        schema._REGISTRY.update(saved)


def test_a_ros1_definition_s_byte_is_int8() -> None:
    """genmsg: ROS 1's ``byte`` is a deprecated ``int8``; rosidl's is an ``octet``."""
    from robomodel.runtime.msg._from_definition import build_message_class
    from robomodel.runtime.msg.definition import parse_message

    text = "byte b\nchar c\n"
    definition = parse_message(text, "pkg/msg/B", where="test")["pkg/msg/B"]
    ros1 = build_message_class("pkg/msg/B", definition, get_message_type, ros1=True)
    ros2 = build_message_class("pkg/msg/B", definition, get_message_type)
    assert ros1.__fields__ == (("b", "int8"), ("c", "char"))
    assert ros2.__fields__ == (("b", "byte"), ("c", "char"))
