"""ROS 1 tf as the turtle_tf tutorials use it: frames named with a leading ``/`` (tf strips
one, as Debian's tf/listener.py's ``strip_leading_slash``), and ``tf.msg.tfMessage`` with the
md5sum of Debian's ``tf/tfMessage``."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from robomodel.clientlibs import tf
from robomodel.clientlibs.genpy import Time
from robomodel.clientlibs.messages import message_class

DEBIAN_TF_MESSAGE = Path("/usr/lib/python3/dist-packages/tf/msg/_tfMessage.py")


def _turtle_in_world() -> tf.Transformer:
    stamped = message_class("geometry_msgs/msg/TransformStamped", "genpy")()
    stamped.header.frame_id, stamped.child_frame_id = "world", "turtle1"
    stamped.header.stamp = Time(10)
    stamped.transform.translation.x, stamped.transform.translation.y = 5.0, 2.0
    stamped.transform.rotation.w = 1.0
    transformer = tf.Transformer()
    transformer.setTransform(stamped)
    return transformer


@pytest.mark.parametrize(("target", "source"), [("/world", "/turtle1"), ("world", "turtle1")])
def test_frames_with_a_leading_slash_are_tfs_frames(target: str, source: str) -> None:
    transformer = _turtle_in_world()
    translation, rotation = transformer.lookupTransform(target, source, Time(0))
    assert translation == pytest.approx((5.0, 2.0, 0.0)) and rotation == pytest.approx((0, 0, 0, 1))
    assert transformer.canTransform(target, source, Time(0))
    assert transformer.getLatestCommonTime(source, target) == Time(10)


def test_an_unknown_frame_is_a_lookup_exception_the_tutorial_catches() -> None:
    with pytest.raises((tf.LookupException, tf.ConnectivityException, tf.ExtrapolationException)):
        _turtle_in_world().lookupTransform("/turtle2", "/turtle1", Time(0))


def test_tf_msg_tfmessage_is_ros1_tfs_message() -> None:
    from robomodel.clientlibs.tf.msg import tfMessage

    if not DEBIAN_TF_MESSAGE.exists():
        pytest.fail(f"Debian's tf is missing ({DEBIAN_TF_MESSAGE}): tools/system-deps installs it")
    md5 = re.search(r'_md5sum = "([0-9a-f]{32})"', DEBIAN_TF_MESSAGE.read_text())
    assert md5 is not None and tfMessage._md5sum == md5.group(1)
    transforms = [message_class("geometry_msgs/msg/TransformStamped", "genpy")()]
    assert tfMessage(transforms).transforms == transforms  # genpy's positional constructor
