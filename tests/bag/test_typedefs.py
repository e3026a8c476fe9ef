"""The schemas and hashes written into bags match rosbags' Jazzy type store (an independent
implementation of rosbag2's message definitions and REP 2016 hashes), type by type."""

from __future__ import annotations

import pytest

from robomodel.bag.typedefs import rihs01, ros2msg_definition
from robomodel.runtime.msg import get_message_type, message_type_names


def _jazzy() -> object:
    from rosbags.typesys import Stores, get_typestore

    return get_typestore(Stores.ROS2_JAZZY)


STORE = _jazzy()
SHARED = sorted(n for n in message_type_names() if n in STORE.fielddefs)  # type: ignore[attr-defined]


def test_most_types_are_compared() -> None:
    assert len(SHARED) >= 30 and "tf2_msgs/msg/TFMessage" in SHARED


@pytest.mark.parametrize("name", SHARED)
def test_definition_and_hash_match_rosbags(name: str) -> None:
    cls = get_message_type(name)
    definition, _ = STORE.generate_msgdef(name, ros_version=2)  # type: ignore[attr-defined]
    assert ros2msg_definition(cls) == definition
    assert rihs01(cls) == STORE.hash_rihs01(name)  # type: ignore[attr-defined]
