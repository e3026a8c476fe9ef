"""A camera frame, its plain green image and a red cube in front of it, for the Camera
display's "View through the camera" browser test, published from their own process.

``python -m tests.viewer.camera_view_publisher DOMAIN`` publishes on the Zenoh bus, 4 times a
second until interrupted (fixed frame ``map``): /tf placing ``camera_optical`` at
``CAMERA_XYZ`` looking along map's +y (optical +z forward, +y down = map's -z), an 8x8 green
rgb8 image on /camera/image_raw with its /camera/camera_info (fx = fy = 8 px: a 53 degree
field of view), and a red cube Marker on /cube ``CUBE_AHEAD_M`` ahead of the camera.
"""

from __future__ import annotations

import sys

import numpy as np

from robomodel.runtime.context import Context
from robomodel.runtime.msg import TFMessage, TransformStamped, get_message_type
from tests.viewer.fed_viewer import publish_stamped_until_stopped

CAMERA_XYZ = (0.0, -3.0, 1.0)
CAMERA_XYZW = (-(0.5**0.5), 0.0, 0.0, 0.5**0.5)  # -90 degrees about x: optical z = map +y
CUBE_AHEAD_M = 2.0
CUBE_SIZE_M = 0.5
IMAGE_SIZE_PX = 8
FOCAL_PX = 8.0
GREEN = (0, 255, 0)


def image(types: dict[str, type]) -> object:
    rgb = np.zeros((IMAGE_SIZE_PX, IMAGE_SIZE_PX, 3), np.uint8)
    rgb[...] = GREEN
    n = IMAGE_SIZE_PX
    msg = types["Image"](height=n, width=n, encoding="rgb8", step=3 * n, data=list(rgb.tobytes()))  # fmt: skip
    msg.header.frame_id = "camera_optical"
    return msg


def camera_info(types: dict[str, type]) -> object:
    n, f, c = IMAGE_SIZE_PX, FOCAL_PX, IMAGE_SIZE_PX / 2
    info = types["CameraInfo"](height=n, width=n)
    info.header.frame_id = "camera_optical"
    info.p = [f, 0.0, c, 0.0, 0.0, f, c, 0.0, 0.0, 0.0, 1.0, 0.0]
    return info


def cube(types: dict[str, type]) -> object:
    m = types["Marker"]()
    m.header.frame_id = "map"
    m.ns, m.id, m.type, m.action = "view", 0, 1, 0  # CUBE, ADD
    x, y, z = CAMERA_XYZ
    m.pose.position.x, m.pose.position.y, m.pose.position.z = x, y + CUBE_AHEAD_M, z
    m.pose.orientation.w = 1.0
    m.scale.x = m.scale.y = m.scale.z = CUBE_SIZE_M
    m.color.r, m.color.a = 1.0, 1.0
    return m


def main(domain: int) -> None:
    types = {n: get_message_type(f"{pkg}/msg/{n}") for n, pkg in (
        ("Image", "sensor_msgs"), ("CameraInfo", "sensor_msgs"), ("Marker", "visualization_msgs"))}  # fmt: skip
    context = Context("zenoh", domain_id=domain)
    node = context.create_node("camera_view_publisher")
    pubs = {topic: node.create_publisher(t, topic, 10) for topic, t in (
        ("/camera/image_raw", types["Image"]), ("/camera/camera_info", types["CameraInfo"]),
        ("/cube", types["Marker"]), ("/tf", TFMessage))}  # fmt: skip
    pose = TransformStamped()
    pose.header.frame_id, pose.child_frame_id = "map", "camera_optical"
    t, q = pose.transform.translation, pose.transform.rotation
    t.x, t.y, t.z = CAMERA_XYZ
    q.x, q.y, q.z, q.w = CAMERA_XYZW
    messages = {"/camera/image_raw": image(types), "/camera/camera_info": camera_info(types),
                "/cube": cube(types)}  # fmt: skip

    publish_stamped_until_stopped(context, node, pubs, pose, messages)


if __name__ == "__main__":
    main(int(sys.argv[1]))
