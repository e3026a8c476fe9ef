"""Marker and MarkerArray displays without a browser: RViz's add, modify, delete, deleteall,
lifetime, namespaces, frame_locked and placement through TF (visualization_msgs/Marker)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robomodel.runtime.msg import get_message_type
from robomodel.viewer.displays import StatusLevel, display_class
from robomodel.viewer.displays.marker_geometry import MARKER_TYPES, marker_drawables
from robomodel.viewer.meshes import MeshPart
from tests.viewer.fake_scene import FakeClock, FakeScene, fake_context, lookup_from

Marker = get_message_type("visualization_msgs/msg/Marker")
MarkerArray = get_message_type("visualization_msgs/msg/MarkerArray")
Point = get_message_type("geometry_msgs/msg/Point")
ColorRGBA = get_message_type("std_msgs/msg/ColorRGBA")


def marker(ns: str = "", id_: int = 0, *, type_: int = 1, action: int = 0, frame: str = "base_link", x: float = 1.0, rgb: tuple[float, float, float] = (1.0, 0.0, 0.0), lifetime_s: float = 0.0, frame_locked: bool = False) -> object:  # fmt: skip
    m = Marker()
    m.header.frame_id = frame
    m.ns, m.id, m.type, m.action = ns, id_, type_, action
    m.pose.position.x = x
    m.scale.x = m.scale.y = m.scale.z = 0.2
    m.color.r, m.color.g, m.color.b = rgb
    m.color.a = 1.0
    m.lifetime.sec = int(lifetime_s)
    m.lifetime.nanosec = int((lifetime_s % 1) * 1e9)
    m.frame_locked = frame_locked
    return m


def rot_z(angle_rad: float, xyz: tuple[float, float, float] = (0, 0, 0)) -> np.ndarray:
    T = np.eye(4)
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    T[:2, :2] = [[c, -s], [s, c]]
    T[:3, 3] = xyz
    return T


@pytest.fixture
def setup() -> tuple[FakeScene, FakeClock, object]:
    scene, clock = FakeScene(), FakeClock()
    display = display_class("rviz/Marker")("Marker", fake_context(scene, clock=clock))
    return scene, clock, display


def test_a_cube_is_placed_through_tf_in_the_fixed_frame(setup) -> None:
    scene, _clock, display = setup
    display.receive(marker(x=1.0))
    status = display.draw(lookup_from({"base_link": rot_z(math.pi / 2, (0, 0, 0.5))}))
    assert status.level is StatusLevel.OK and status.text == "1 messages received"
    (node,) = scene.visible("/displays/Marker/").values()
    assert node.kind == "mesh_simple" and node.kwargs["color"] == (255, 0, 0)
    np.testing.assert_allclose(node.position, (0.0, 1.0, 0.5), atol=1e-9)
    extent = node.kwargs["vertices"].max(axis=0) - node.kwargs["vertices"].min(axis=0)
    np.testing.assert_allclose(extent, (0.2, 0.2, 0.2), atol=1e-6)


def test_modify_replaces_the_marker_of_the_same_ns_and_id(setup) -> None:
    scene, _clock, display = setup
    lookup = lookup_from({"base_link": np.eye(4)})
    display.receive(marker(rgb=(1, 0, 0)))
    display.draw(lookup)
    display.receive(marker(rgb=(0, 0, 1), x=2.0))
    display.draw(lookup)
    (node,) = scene.visible().values()
    assert node.kwargs["color"] == (0, 0, 255) and node.position[0] == pytest.approx(2.0)


def test_delete_and_deleteall(setup) -> None:
    scene, _clock, display = setup
    lookup = lookup_from({"base_link": np.eye(4)})
    for ns, i in [("a", 0), ("a", 1), ("b", 0)]:
        display.receive(marker(ns, i))
    display.draw(lookup)
    assert len(scene.visible()) == 3
    display.receive(marker("a", 1, action=2))  # DELETE
    display.draw(lookup)
    assert sorted(display.store.markers) == [("a", 0), ("b", 0)] and len(scene.nodes) == 2
    display.receive(marker("b", 5, action=3))  # DELETEALL of ns b (RViz 2)
    display.draw(lookup)
    assert sorted(display.store.markers) == [("a", 0)] and len(scene.nodes) == 1
    display.receive(marker("", 0, action=3))  # DELETEALL without ns: everything
    display.draw(lookup)
    assert display.store.markers == {} and scene.nodes == {}


def test_lifetime_removes_a_marker_after_it(setup) -> None:
    scene, clock, display = setup
    lookup = lookup_from({"base_link": np.eye(4)})
    display.receive(marker("short", lifetime_s=0.5))
    display.receive(marker("forever"))
    display.draw(lookup)
    clock.ns += 400_000_000
    display.draw(lookup)
    assert len(scene.nodes) == 2
    clock.ns += 200_000_000
    display.draw(lookup)
    assert list(display.store.markers) == [("forever", 0)] and len(scene.nodes) == 1


def test_a_namespace_switched_off_hides_its_markers_until_on_again(setup) -> None:
    scene, _clock, display = setup
    lookup = lookup_from({"base_link": np.eye(4)})
    display.receive(marker("walls", 0))
    display.receive(marker("goals", 0))
    display.draw(lookup)
    assert dict(display.option("Namespaces")) == {"walls": True, "goals": True}
    display.set_namespace_enabled("walls", False)
    display.draw(lookup)
    assert len(scene.visible()) == 1 and ("walls", 0) in display.store.markers
    display.receive(marker("walls", 1))  # still received while hidden
    display.draw(lookup)
    assert len(scene.visible()) == 1
    display.set_namespace_enabled("walls", True)
    display.draw(lookup)
    assert len(scene.visible()) == 3


def test_frame_locked_markers_follow_their_frame_and_others_stay(setup) -> None:
    scene, _clock, display = setup
    frames = {"base_link": np.eye(4)}
    display.receive(marker("locked", frame_locked=True))
    display.receive(marker("placed"))
    display.draw(lookup_from(frames))
    frames["base_link"] = rot_z(0.0, (0.0, 3.0, 0.0))
    display.draw(lookup_from(frames))
    by_ns = {n.name.split("/")[3]: n.position for n in scene.visible().values()}
    assert by_ns["ns0"] == pytest.approx((1.0, 3.0, 0.0))  # locked: moved with base_link
    assert by_ns["ns1"] == pytest.approx((1.0, 0.0, 0.0))  # placed once, stays


def test_a_frame_without_transform_is_the_status_and_the_marker_is_hidden(setup) -> None:
    scene, _clock, display = setup
    display.receive(marker("n", 3, frame="camera"))
    status = display.draw(lookup_from({}))
    assert status.level is StatusLevel.ERROR
    assert status.text == "n/3: No transform from [camera] to [map]"
    assert scene.visible() == {}
    status = display.draw(lookup_from({"camera": np.eye(4)}))
    assert status.level is StatusLevel.OK and len(scene.visible()) == 1


def test_no_messages_is_a_warning_and_bad_markers_errors(setup) -> None:
    _scene, _clock, display = setup
    lookup = lookup_from({"base_link": np.eye(4)})
    assert display.draw(lookup).text == "No messages received"
    display.receive(marker(action=7))
    assert display.draw(lookup).text == "Unknown marker action: 7"
    display.store.clear()
    bad = marker(x=float("nan"))
    display.receive(bad)
    assert "invalid floating point" in display.draw(lookup).text
    display.store.clear()
    display.receive(marker(type_=42))
    assert display.draw(lookup).text == "/0: Unknown marker type: 42"


def test_marker_array_applies_every_marker_in_order() -> None:
    scene = FakeScene()
    display = display_class("MarkerArray")("Markers", fake_context(scene))
    array = MarkerArray()
    array.markers = [marker("a", 0), marker("a", 1), marker("", 0, action=3), marker("a", 2)]
    display.receive(array)
    display.draw(lookup_from({"base_link": np.eye(4)}))
    assert list(display.store.markers) == [("a", 2)]
    assert list(scene.nodes) == ["/displays/Markers/ns0/2/0"]


def _with_points(m: object, points: list[tuple[float, float, float]], colors: list[tuple[float, float, float]] | None = None) -> object:  # fmt: skip
    m.points = [Point(x=p[0], y=p[1], z=p[2]) for p in points]
    m.colors = [ColorRGBA(r=c[0], g=c[1], b=c[2], a=1.0) for c in colors or []]
    return m


@pytest.mark.parametrize("type_", sorted(MARKER_TYPES))
def test_every_marker_type_is_drawn(type_: int) -> None:
    m = marker(type_=type_)
    square = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 0), (1, 1, 0)]
    _with_points(m, square, [(1, 0, 0), (0, 1, 0), (0, 0, 1)] * 2)
    m.text, m.mesh_resource = "hello", "package://x/mesh.stl"
    part = MeshPart(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32), np.array([[0, 1, 2]], np.uint32), None)  # fmt: skip
    (drawable, *rest) = marker_drawables(m, lambda uri: (part,))
    assert not rest
    expected = {
        "ARROW": "mesh_simple", "CUBE": "mesh_simple", "SPHERE": "mesh_simple",
        "CYLINDER": "mesh_simple", "LINE_STRIP": "line_segments", "LINE_LIST": "line_segments",
        "CUBE_LIST": "mesh_trimesh", "SPHERE_LIST": "mesh_trimesh", "POINTS": "point_cloud",
        "TEXT_VIEW_FACING": "image", "MESH_RESOURCE": "mesh_simple",
        "TRIANGLE_LIST": "mesh_trimesh",
    }  # fmt: skip
    assert drawable.kind == expected[MARKER_TYPES[type_]]
    if type_ == 4:  # LINE_STRIP: 5 segments
        assert drawable.kwargs["points"].shape == (5, 2, 3)
    if type_ == 5:  # LINE_LIST: 3 pairs, each point's colour
        assert drawable.kwargs["points"].shape == (3, 2, 3)
        assert drawable.kwargs["colors"][0].tolist() == [[255, 0, 0], [0, 255, 0]]
    if type_ == 9:  # red text (the marker's colour) with a transparent background
        rgba = drawable.kwargs["image"]
        assert drawable.view_facing and (rgba[..., :3] == (255, 0, 0)).all()
        assert rgba[..., 3].max() == 255 and rgba[0, 0, 3] == 0
    if type_ == 10:  # the mesh scaled by scale
        assert drawable.kwargs["vertices"].max() == pytest.approx(0.2)


def test_arrow_proportions_are_rviz_s() -> None:
    m = marker(type_=0)
    m.scale.x, m.scale.y, m.scale.z = 1.0, 0.1, 0.1
    (arrow,) = marker_drawables(m)
    v = arrow.kwargs["vertices"]
    np.testing.assert_allclose(v.min(axis=0), (0.0, -0.1, -0.1), atol=1e-6)  # head 2x shaft
    np.testing.assert_allclose(v.max(axis=0), (1.0, 0.1, 0.1), atol=1e-6)
    _with_points(m, [(0, 0, 0), (0, 0, 2)])
    m.scale.x, m.scale.y, m.scale.z = 0.1, 0.3, 0.0
    (arrow,) = marker_drawables(m)
    v = arrow.kwargs["vertices"]
    np.testing.assert_allclose(v.max(axis=0), (0.15, 0.15, 2.0), atol=1e-6)


def test_a_triangle_list_of_the_wrong_length_is_refused() -> None:
    scene = FakeScene()
    display = display_class("Marker")("M", fake_context(scene))
    display.receive(_with_points(marker(type_=11), [(0, 0, 0), (1, 0, 0)]))
    status = display.draw(lookup_from({"base_link": np.eye(4)}))
    assert status.level is StatusLevel.ERROR and "not a multiple of 3" in status.text


def test_text_is_in_the_marker_s_colour_alpha_and_height_and_faces_the_camera() -> None:
    scene = FakeScene()
    context = fake_context(scene)
    view = (0.5, -0.5, 0.5, -0.5)
    context.view_wxyz = lambda: view
    display = display_class("Marker")("M", context)
    m = marker(type_=9, rgb=(0.0, 1.0, 0.0))
    m.text, m.color.a, m.scale.z = "two\nlines", 0.5, 0.3
    m.pose.orientation.z, m.pose.orientation.w = 1.0, 0.0  # ignored: the text faces the camera
    display.receive(m)
    display.draw(lookup_from({"base_link": np.eye(4)}))
    (node,) = scene.visible().values()
    rgba = node.kwargs["image"]
    assert (rgba[..., :3] == (0, 255, 0)).all() and rgba[..., 3].max() == 128  # alpha 0.5
    ink_rows = np.flatnonzero(rgba[..., 3].max(axis=1) > 0)
    metres_per_px = node.kwargs["render_height"] / rgba.shape[0]
    # two lines of 0.3 m: the ink spans more than one line and less than two
    assert 0.3 < (ink_rows[-1] - ink_rows[0] + 1) * metres_per_px < 0.6
    assert tuple(node.wxyz) == view and tuple(node.position) == pytest.approx((1.0, 0.0, 0.0))
    view = (1.0, 0.0, 0.0, 0.0)
    display.draw(lookup_from({"base_link": np.eye(4)}))
    assert tuple(node.wxyz) == view


def test_a_textured_mesh_resource_keeps_its_texture_only_with_embedded_materials(tmp_path) -> None:
    from robomodel.viewer.meshes import load_mesh_file
    from tests.viewer.textured import write_textured_cube

    parts = load_mesh_file(write_textured_cube(tmp_path))
    m = marker(type_=10, rgb=(0.0, 0.0, 0.0))
    m.color.a = 0.0  # an all-zero colour: no tint (test_marker_mesh_tint.py tints)
    m.mesh_resource, m.mesh_use_embedded_materials = "file:///cube.dae", True
    m.scale.x, m.scale.y, m.scale.z = 1.0, 2.0, 3.0
    (textured,) = marker_drawables(m, lambda uri: parts)
    assert textured.kind == "glb" and textured.kwargs["glb_data"] == parts[0].glb
    assert textured.kwargs["scale"] == (1.0, 2.0, 3.0)
    m.mesh_use_embedded_materials = False
    m.color.r, m.color.g, m.color.a = 1.0, 1.0, 1.0
    (plain,) = marker_drawables(m, lambda uri: parts)
    assert plain.kind == "mesh_simple" and plain.kwargs["color"] == (255, 255, 0)


def test_a_marker_sent_again_keeps_its_nodes_and_is_placed_anew(setup) -> None:
    scene, _clock, display = setup
    lookup = lookup_from({"base_link": np.eye(4)})
    display.receive(marker(x=1.0))
    display.draw(lookup)
    (first,) = scene.visible().values()
    display.receive(marker(x=2.0))  # moved: the same node, placed anew
    display.draw(lookup)
    (again,) = scene.visible().values()
    assert again is first and again.position[0] == pytest.approx(2.0)
    display.receive(marker(x=2.0, rgb=(0.0, 0.0, 1.0)))  # another colour: a new node
    display.draw(lookup)
    (recoloured,) = scene.visible().values()
    assert recoloured is not first and recoloured.kwargs["color"] == (0, 0, 255)
