"""Known messages for the display browser tests, published from their own process.

``python -m tests.viewer.display_publisher DOMAIN`` publishes on the Zenoh bus, 4 times a
second until interrupted: a 3-point cloud on /cloud (red, green and blue points, rgb field),
a 4x4 red/blue checkerboard on /camera/image_raw with its /camera/camera_info, a 4x4
occupancy grid on /map (free, occupied and unknown cells), a PoseStamped on /pose in a frame
TF does not have, an Odometry pose on /odom and a Path on /path, and /tf placing ``camera_optical`` 1 m above (2, -2.5) in ``map``, looking down.
"""

from __future__ import annotations

import struct
import sys

import numpy as np

from robomodel.runtime.context import Context
from robomodel.runtime.msg import TFMessage, TransformStamped, get_message_type
from tests.viewer.fed_viewer import publish_stamped_until_stopped

# where the test expects them (fixed frame: map) -----------------------------------------------
CLOUD_POINTS = (((1.0, 0.0, 0.0), 0xFF0000), ((0.0, 1.0, 0.0), 0x00FF00), ((-1.0, -1.0, 0.0), 0x0000FF))  # fmt: skip
MAP_ORIGIN = (-3.0, 1.0)  # the grid's cell (0, 0) corner in map [m]
MAP_RESOLUTION = 0.5
# row 0 is the map's bottom (y = 1.0 .. 1.5): free, occupied, unknown, free ...
MAP_CELLS = np.array(
    [[0, 100, -1, 0], [100, 0, 0, -1], [-1, -1, 100, 100], [0, 0, 0, 100]], dtype=np.int8
)
BOARD = np.indices((4, 4)).sum(axis=0) % 2 == 0  # red where True, blue elsewhere
ODOM_XY = (-2.5, -1.0)  # an arrow from here along +x (RViz's default: 1.3 m long)
PATH_XY = ((-3.0, -2.0), (-1.0, -2.0))


def cloud(msg_types: dict[str, type]) -> object:
    data = b"".join(struct.pack("<fff4xI", *p, c) for p, c in CLOUD_POINTS)
    PointField = msg_types["PointField"]
    msg = msg_types["PointCloud2"](height=1, width=3, point_step=20, row_step=60, data=list(data), is_dense=True)  # fmt: skip
    msg.fields = [PointField(name=n, offset=o, datatype=7, count=1)
                  for n, o in (("x", 0), ("y", 4), ("z", 8), ("rgb", 16))]  # fmt: skip
    msg.header.frame_id = "map"
    return msg


def image(msg_types: dict[str, type]) -> object:
    rgb = np.where(BOARD[..., None], (255, 0, 0), (0, 0, 255)).astype(np.uint8)
    msg = msg_types["Image"](height=4, width=4, encoding="rgb8", step=12, data=list(rgb.tobytes()))  # fmt: skip
    msg.header.frame_id = "camera_optical"
    return msg


def camera_info(msg_types: dict[str, type]) -> object:
    info = msg_types["CameraInfo"](height=4, width=4)
    info.header.frame_id = "camera_optical"
    info.p = [4.0, 0.0, 2.0, 0.0, 0.0, 4.0, 2.0, 0.0, 0.0, 0.0, 1.0, 0.0]
    return info


def occupancy(msg_types: dict[str, type]) -> object:
    msg = msg_types["OccupancyGrid"]()
    msg.header.frame_id = "map"
    msg.info.resolution, msg.info.width, msg.info.height = MAP_RESOLUTION, 4, 4
    msg.info.origin.position.x, msg.info.origin.position.y = MAP_ORIGIN
    msg.info.origin.orientation.w = 1.0
    msg.data = [int(v) for v in MAP_CELLS.ravel()]
    return msg


def odometry(msg_types: dict[str, type]) -> object:
    msg = msg_types["Odometry"]()
    msg.header.frame_id = "map"
    msg.pose.pose.position.x, msg.pose.pose.position.y = ODOM_XY
    msg.pose.pose.orientation.w = 1.0
    return msg


def path(msg_types: dict[str, type]) -> object:
    msg = msg_types["Path"]()
    msg.header.frame_id = "map"
    for x, y in PATH_XY:
        pose = msg_types["PoseStamped"]()
        pose.pose.position.x, pose.pose.position.y = x, y
        pose.pose.orientation.w = 1.0
        msg.poses.append(pose)
    return msg


def main(domain: int) -> None:
    names = {"PointCloud2": "sensor_msgs", "PointField": "sensor_msgs", "Image": "sensor_msgs",
             "CameraInfo": "sensor_msgs", "OccupancyGrid": "nav_msgs", "PoseStamped": "geometry_msgs",
             "Odometry": "nav_msgs", "Path": "nav_msgs"}  # fmt: skip
    types = {n: get_message_type(f"{pkg}/msg/{n}") for n, pkg in names.items()}
    context = Context("zenoh", domain_id=domain)
    node = context.create_node("display_publisher")
    pubs = {topic: node.create_publisher(t, topic, 10) for topic, t in (
        ("/cloud", types["PointCloud2"]), ("/camera/image_raw", types["Image"]),
        ("/camera/camera_info", types["CameraInfo"]), ("/map", types["OccupancyGrid"]),
        ("/pose", types["PoseStamped"]), ("/tf", TFMessage), ("/odom", types["Odometry"]),
        ("/path", types["Path"]))}  # fmt: skip
    pose = types["PoseStamped"]()
    pose.header.frame_id = "nowhere"
    pose.pose.orientation.w = 1.0
    lift = TransformStamped()
    lift.header.frame_id, lift.child_frame_id = "map", "camera_optical"
    lift.transform.translation.x, lift.transform.translation.y = 2.0, -2.5  # clear of the rest
    lift.transform.translation.z = 1.0
    lift.transform.rotation.x, lift.transform.rotation.w = 1.0, 0.0  # looking down
    messages = {"/cloud": cloud(types), "/camera/image_raw": image(types), "/pose": pose,
                "/camera/camera_info": camera_info(types), "/map": occupancy(types),
                "/odom": odometry(types), "/path": path(types)}  # fmt: skip

    publish_stamped_until_stopped(context, node, pubs, lift, messages)


if __name__ == "__main__":
    main(int(sys.argv[1]))
