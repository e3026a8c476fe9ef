"""The DisplayManager on a real (in-process) node: subscriptions follow each display's Topic,
end with it, and a type that cannot be found is the display's status, asked for once."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest

from robomodel.runtime.context import Context
from robomodel.runtime.msg import get_message_type
from robomodel.tf.buffer import BufferCore
from robomodel.tf.message import TransformStamped
from robomodel.viewer.displays import Display, StatusLevel
from robomodel.viewer.displays.base import Option, OptionKind
from robomodel.viewer.displays.manager import DisplayManager, DisplayNameError
from tests.viewer.fake_scene import FakeScene, fake_context

Marker = get_message_type("visualization_msgs/msg/Marker")


@pytest.fixture
def context() -> Iterator[Context]:
    with Context("inproc") as ctx:
        yield ctx


def _manager(context: Context) -> tuple[DisplayManager, FakeScene]:
    scene = FakeScene()
    node = context.create_node("viewer")
    return DisplayManager(fake_context(scene, fixed="base_link"), node, BufferCore()), scene


def _cube(frame: str = "base_link") -> object:
    m = Marker()
    m.header.frame_id, m.type = frame, 1
    m.scale.x = m.scale.y = m.scale.z = m.color.a = 1.0
    return m


def test_displays_hear_their_topic_and_follow_a_new_one(context: Context) -> None:
    manager, scene = _manager(context)
    display = manager.add("rviz_default_plugins/Marker", values={"Topic": "/a"})
    publisher = context.create_node("pub")
    on_a = publisher.create_publisher(Marker, "/a", 10)
    on_b = publisher.create_publisher(Marker, "/b", 10)
    manager.update()  # subscribes
    on_a.publish(_cube())
    context.spin_once(0.0)
    manager.update()
    assert display.messages_received == 1 and display.status.level is StatusLevel.OK
    assert len(scene.visible("/displays/Marker/")) == 1
    display.set_option("Topic", "/b")  # a new topic starts empty (RViz's onTopicChanged)
    manager.update()
    assert scene.nodes == {} and display.status.text == "No messages received"
    on_a.publish(_cube())
    on_b.publish(_cube())
    context.spin_once(0.0)
    manager.update()
    assert display.messages_received == 1
    manager.remove(display)
    on_b.publish(_cube())
    context.spin_once(0.0)
    assert display.messages_received == 1 and manager.displays == []


def test_a_message_of_the_old_topic_queued_before_a_change_does_not_count(
    context: Context,
) -> None:
    """The page changes the Topic between two of the manager's ticks while a message of the
    old topic waits in the executor: it is dropped, as RViz's reset on a topic change."""
    manager, _scene = _manager(context)
    display = manager.add("Marker", values={"Topic": "/a"})
    on_a = context.create_node("pub").create_publisher(Marker, "/a", 10)
    manager.update()
    on_a.publish(_cube())  # queued, not yet delivered
    display.set_option("Topic", "/nothing_here")
    context.spin_once(0.0)
    manager.update()
    assert display.messages_received == 0
    assert display.status.text == "No messages received"


def test_the_fixed_frame_and_tf_place_markers(context: Context) -> None:
    manager, scene = _manager(context)
    display = manager.add("Marker")
    display.receive(_cube("odom"))
    manager.update()
    assert display.status.text == "/0: Frame [odom] does not exist"
    odom = TransformStamped("base_link", "odom", translation_m=(2.0, 0.0, 0.0))
    assert manager.buffer.set_transform(odom, "test", is_static=True)
    manager.update()
    assert display.status.level is StatusLevel.OK
    (node,) = scene.visible().values()
    np.testing.assert_allclose(node.position, (2.0, 0.0, 0.0))


def test_names_are_unique_and_renames_checked(context: Context) -> None:
    manager, _scene = _manager(context)
    first, second = manager.add("Marker"), manager.add("Marker")
    assert (first.name, second.name) == ("Marker", "Marker (2)")
    with pytest.raises(DisplayNameError, match="already named 'Marker'"):
        manager.rename(second, "Marker")
    with pytest.raises(DisplayNameError, match="needs a name"):
        manager.rename(second, "  ")
    manager.rename(second, "Goals")
    assert second.root == "/displays/Goals"


class _Unknown(Display):
    class_name = "NoSuchTypeDisplay"
    message_types = ("no_such_msgs/msg/Nothing",)
    options = (Option("Topic", "/x", OptionKind.TOPIC),)


def test_a_type_that_cannot_be_found_is_the_status_and_asked_for_once(
    context: Context, monkeypatch: pytest.MonkeyPatch
) -> None:
    import robomodel.viewer.displays.base as base_module
    import robomodel.viewer.displays.manager as manager_module

    base_module.display_classes()  # the built-in ones loaded first
    monkeypatch.setitem(base_module._REGISTRY, _Unknown.class_name, _Unknown)  # this test only
    asked: list[str] = []
    real = manager_module.get_message_type

    def counting(name: str) -> object:
        asked.append(name)
        return real(name)

    monkeypatch.setattr(manager_module, "get_message_type", counting)
    manager, _scene = _manager(context)
    display = manager.add("NoSuchTypeDisplay")
    manager.update()
    manager.update()
    assert display.status.level is StatusLevel.ERROR
    assert display.status.text.startswith("Error subscribing: ")
    assert asked == ["no_such_msgs/msg/Nothing"]
