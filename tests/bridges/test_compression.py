"""rosbridge's compressions as data, read back with decoders the bridge does not use (cbor2's
loads, Pillow): fixed-size arrays as typed arrays, ROS 1's times, bool and string arrays as
lists, and PNG images of the shortest texts."""

from __future__ import annotations

import base64
import io
import struct

import cbor2
from PIL import Image

from robomodel.bridges.compression import cbor_frame, png_encode
from robomodel.runtime.msg import get_message_type


def test_cbor_fixed_arrays_times_and_lists() -> None:
    info = get_message_type("sensor_msgs/msg/CameraInfo")(k=[float(i) for i in range(9)])
    info.header.stamp.sec, info.header.stamp.nanosec = 1, 2
    ros1 = cbor2.loads(cbor_frame("/info", info, "ros1"))["msg"]
    assert ros1["k"] == cbor2.CBORTag(86, struct.pack("<9d", *range(9)))
    assert ros1["header"]["stamp"] == {"secs": 1, "nsecs": 2}
    ros2 = cbor2.loads(cbor_frame("/info", info, "ros2"))["msg"]
    assert ros2["header"]["stamp"] == {"sec": 1, "nanosec": 2}
    flags = get_message_type("std_msgs/msg/ByteMultiArray")(data=b"\x01\xfe")
    assert cbor2.loads(cbor_frame("/b", flags, "ros2"))["msg"]["data"] == b"\x01\xfe"
    names = get_message_type("sensor_msgs/msg/JointState")(name=["a", "b"])
    assert cbor2.loads(cbor_frame("/j", names, "ros2"))["msg"]["name"] == ["a", "b"]


def test_png_of_short_and_multibyte_texts() -> None:
    for text in ("{", "{}", '{"é": 1}', "x" * 1000):
        image = Image.open(io.BytesIO(base64.b64decode(png_encode(text))))
        assert image.tobytes().decode("utf-8").rstrip("\n") == text
