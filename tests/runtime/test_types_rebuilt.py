"""A class built from a definition before the type sources changed is still its type.

``configure`` (``--package-path``, ``--distro``) forgets the classes built from definitions, so
code that held ``get_message_type("sensor_msgs/msg/Image")`` from before has a different class
object than code asking afterwards. CI saw the in-process bus refuse to deliver between the two
("published as sensor_msgs/msg/Image but subscribed as sensor_msgs/msg/Image") and ROS 1 refuse
the older class; both now compare the type's name and hash.
"""

from __future__ import annotations

from typing import Any

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
