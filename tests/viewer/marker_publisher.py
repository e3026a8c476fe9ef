"""Known text, mesh and covariance messages for browser tests, published from their own process.

``python -m tests.viewer.marker_publisher DOMAIN MESH_DIR`` writes a textured cube into
MESH_DIR (tests/viewer/textured.py) and publishes on the Zenoh bus, 4 times a second until
interrupted (fixed frame ``map``):

- /text (Marker): TEXT_VIEW_FACING markers, "HH" in opaque green and "HH" in half-transparent
  red, ``TEXT_HEIGHT_M`` high;
- /meshes (MarkerArray): the textured cube with ``mesh_use_embedded_materials`` and an
  all-zero colour (its red/blue checker), the same with blue (0, 0, 1, 1), which RViz 2 draws
  half over the texture (red turns purple), and the same file without (the marker's yellow);
- /pose_cov (PoseWithCovarianceStamped): a pose with a known position and orientation
  covariance.
"""

from __future__ import annotations

import sys
from pathlib import Path

from robomodel.runtime.context import Context
from robomodel.runtime.msg import get_message_type
from tests.viewer.fed_viewer import publish_until_stopped
from tests.viewer.textured import write_textured_cube

TEXT_HEIGHT_M = 0.6
GREEN_TEXT_XYZ = (-1.5, 0.0, 0.6)
RED_TEXT_XYZ = (-1.5, 0.0, -0.6)
TEXTURED_XYZ = (-1.5, 0.0, 0.0)
YELLOW_XYZ = (0.0, 0.0, 0.0)
TINTED_XYZ = (0.0, 0.0, 1.2)
MESH_SCALE = 2.0  # the 0.4 m cube drawn 0.8 m wide
COVARIANCE_XYZ = (0.0, 0.0, 0.0)
# position variances (x, y, z) [m^2] and orientation variances (roll, pitch, yaw) [rad^2]
POSITION_VARIANCE = (1.0, 0.25, 0.0625)
ORIENTATION_VARIANCE = (0.04, 0.09, 0.16)


def _marker(types: dict[str, type], id_: int, type_: int, xyz: tuple[float, float, float], rgba: tuple[float, float, float, float]) -> object:  # fmt: skip
    m = types["Marker"]()
    m.header.frame_id = "map"
    m.ns, m.id, m.type, m.action = "test", id_, type_, 0
    m.pose.position.x, m.pose.position.y, m.pose.position.z = xyz
    m.pose.orientation.w = 1.0
    m.color.r, m.color.g, m.color.b, m.color.a = rgba
    return m


def texts(types: dict[str, type]) -> list[object]:
    out = []
    for id_, xyz, rgba in ((0, GREEN_TEXT_XYZ, (0.0, 1.0, 0.0, 1.0)), (1, RED_TEXT_XYZ, (1.0, 0.0, 0.0, 0.5))):  # fmt: skip
        m = _marker(types, id_, 9, xyz, rgba)
        m.text, m.scale.z = "HH", TEXT_HEIGHT_M
        out.append(m)
    return out


def meshes(types: dict[str, type], dae: Path) -> object:
    array = types["MarkerArray"]()
    for id_, xyz, embedded, rgba in ((0, TEXTURED_XYZ, True, (0.0, 0.0, 0.0, 0.0)),
                                     (1, YELLOW_XYZ, False, (1.0, 1.0, 0.0, 1.0)),
                                     (2, TINTED_XYZ, True, (0.0, 0.0, 1.0, 1.0))):  # fmt: skip
        m = _marker(types, id_, 10, xyz, rgba)
        m.mesh_resource, m.mesh_use_embedded_materials = dae.as_uri(), embedded
        m.scale.x = m.scale.y = m.scale.z = MESH_SCALE
        array.markers.append(m)
    return array


def pose_with_covariance(types: dict[str, type]) -> object:
    msg = types["PoseWithCovarianceStamped"]()
    msg.header.frame_id = "map"
    msg.pose.pose.position.x, msg.pose.pose.position.y, msg.pose.pose.position.z = COVARIANCE_XYZ
    msg.pose.pose.orientation.w = 1.0
    cov = [0.0] * 36
    for i, v in enumerate((*POSITION_VARIANCE, *ORIENTATION_VARIANCE)):
        cov[i * 6 + i] = v
    msg.pose.covariance = cov
    return msg


def main(domain: int, mesh_dir: Path) -> None:
    names = {"Marker": "visualization_msgs", "MarkerArray": "visualization_msgs",
             "PoseWithCovarianceStamped": "geometry_msgs"}  # fmt: skip
    types = {n: get_message_type(f"{pkg}/msg/{n}") for n, pkg in names.items()}
    dae = write_textured_cube(mesh_dir)
    context = Context("zenoh", domain_id=domain)
    node = context.create_node("marker_publisher")
    text_pub = node.create_publisher(types["Marker"], "/text", 10)
    mesh_pub = node.create_publisher(types["MarkerArray"], "/meshes", 10)
    cov_pub = node.create_publisher(types["PoseWithCovarianceStamped"], "/pose_cov", 10)
    text_msgs, mesh_msg, cov_msg = texts(types), meshes(types, dae), pose_with_covariance(types)

    def publish() -> None:
        for m in text_msgs:
            text_pub.publish(m)
        mesh_pub.publish(mesh_msg)
        cov_pub.publish(cov_msg)

    publish_until_stopped(context, node, publish)


if __name__ == "__main__":
    main(int(sys.argv[1]), Path(sys.argv[2]))
