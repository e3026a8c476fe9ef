"""A bag holding a type that no package, store or hand-written class has (written by rosbags
with its definition, as ros2 bag stores it): robomodel's bag info lists it and bag play
decodes it by the bag's own definition."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from robomodel.bag import open_bag
from robomodel.bag.player import _decoder
from robomodel.runtime.msg import message_to_dict
from tests.conftest import ROBOMODEL
from tests.timing import scaled

DEFINITION = (
    "geometry_msgs/Point where\nuint8 level\nstring[] tags\n" + "=" * 80 + "\n"
    "MSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n"
)


@pytest.mark.parametrize("plugin", ["SQLITE3", "MCAP"])
def test_play_decodes_by_the_bags_definition(tmp_path: Path, plugin: str) -> None:
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    store = get_typestore(Stores.ROS2_JAZZY)
    store.register(get_types_from_msg(DEFINITION, "bag_msgs/msg/Sample"))
    sample = store.types["bag_msgs/msg/Sample"]
    point = store.types["geometry_msgs/msg/Point"]

    folder = tmp_path / "bag"
    with Writer(folder, version=9, storage_plugin=StoragePlugin[plugin]) as writer:
        conn = writer.add_connection("/sample", "bag_msgs/msg/Sample", typestore=store)
        data = store.serialize_cdr(sample(point(1.0, -2.0, 0.5), 7, ["a", "b"]), conn.msgtype)
        writer.write(conn, 42, data)
    topic = next(t for t in open_bag(folder).summary().topics if t.name == "/sample")
    cls, decode = _decoder(topic)
    (stored,) = list(open_bag(folder).messages())
    assert message_to_dict(decode(stored.data)) == {
        "where": {"x": 1.0, "y": -2.0, "z": 0.5}, "level": 7, "tags": ["a", "b"]
    }  # fmt: skip
    assert cls.__typename__ == "bag_msgs/msg/Sample"
    info = subprocess.run(
        [*ROBOMODEL, "bag", "info", str(folder)], capture_output=True, text=True, timeout=scaled(60)
    )
    assert info.returncode == 0 and "bag_msgs/msg/Sample" in info.stdout, info.stderr
