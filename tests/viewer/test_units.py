"""The viewer's pieces without a browser: ports, file watching, poses, meshes, materials, CLI."""

from __future__ import annotations

import math
import socket
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from robomodel.description import read_urdf
from robomodel.description.model import Joint, JointType, Material, Origin, Robot
from robomodel.description.packages import PackageIndex
from robomodel.errors import PathEscapeError
from robomodel.kinematics.se3 import quat_xyzw_from_matrix
from robomodel.viewer._poses import wxyz_from_matrices
from robomodel.viewer.bodies import body_transform
from robomodel.viewer.errors import PortInUseError
from robomodel.viewer.joint_panel import BodyPose
from robomodel.viewer.materials import material_rgba
from robomodel.viewer.meshes import MeshCache, load_mesh_file, resolve_mesh_uri
from robomodel.viewer.ports import ensure_port_free
from robomodel.viewer.reload import FileWatcher
from tests.conftest import EXAMPLES, ToolResult, example_robot_data_dir
from tests.timing import scaled

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"


def test_port_in_use_names_a_free_one() -> None:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        sock.listen()
        port = sock.getsockname()[1]
        with pytest.raises(PortInUseError) as info:
            ensure_port_free("127.0.0.1", port)
    assert f"port {port} on 127.0.0.1 is already in use" in str(info.value)
    assert info.value.free_port is not None and info.value.free_port > port
    assert f"--port {info.value.free_port}" in str(info.value)


def test_cli_port_in_use_exits_2_with_one_line(cli: Callable[..., ToolResult]) -> None:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        sock.listen()
        port = sock.getsockname()[1]
        result = cli(
            "view",
            str(EXAMPLES / "two_link_arm/urdf/two_link_arm.urdf"),
            "--no-browser",
            "--port",
            str(port),
        )
    assert result.code == 2
    assert (
        result.err.count("\n") == 1
        and "already in use" in result.err
        and "try --port" in result.err
    )


def test_cli_rejects_bad_arguments(
    cli: Callable[..., ToolResult], capsys: pytest.CaptureFixture[str]
) -> None:
    urdf = str(EXAMPLES / "two_link_arm/urdf/two_link_arm.urdf")
    result = cli("view", urdf, "--prefix", "a/", "--prefix", "b/", "--no-browser")
    assert result.code == 2 and "one per FILE" in result.err
    result = cli("view", urdf, "--joint-states", "external", "--no-browser")
    assert result.code == 2 and "--bus zenoh" in result.err
    result = cli("view", "--description-topic", "/r1/robot_description", "--no-browser")
    assert result.code == 2 and "--bus zenoh" in result.err and result.err.count("\n") == 1
    result = cli("view", "--description-topic", "/r1/robot_description", "--prefix", "r1/",
                 "--prefix", "r2/", "--bus", "zenoh", "--no-browser")  # fmt: skip
    assert result.code == 2 and "1 --description-topic(s); give one per FILE, then per topic" in result.err  # fmt: skip
    result = cli("view", "name:=value", "--no-browser")
    assert result.code == 2 and "without a FILE" in result.err
    result = cli("view", "nothere.urdf", "--no-browser", "--port", "0")
    assert result.code == 2 and "no such file" in result.err
    for verb in ("view", "sim"):  # argparse's own usage error: exit 2
        with pytest.raises(SystemExit) as stopped:
            cli(verb, urdf, "--frame-rate", "0", "--no-browser")
        assert stopped.value.code == 2
        assert "--frame-rate: must be 1..1000 Hz, got 0" in capsys.readouterr().err


def test_file_watcher_sees_edits_new_and_removed_files(tmp_path: Path) -> None:
    a, b = tmp_path / "a.xacro", tmp_path / "b.yaml"
    a.write_text("1")
    watcher = FileWatcher([str(a), str(b)])
    assert watcher.changed() == ()
    time.sleep(0.01)
    a.write_text("22")
    b.write_text("x")
    assert set(watcher.changed()) == {str(a), str(b)}
    assert watcher.changed() == ()
    a.unlink()
    assert watcher.changed() == (str(a),)


def test_wxyz_from_matrices_matches_the_kinematics_layer() -> None:
    rng = np.random.default_rng(3)
    q = rng.normal(size=(200, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    R = np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
            np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
            np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
        ],
        axis=1,
    )
    got = wxyz_from_matrices(R)
    for i in range(len(R)):
        ref = np.asarray(quat_xyzw_from_matrix(R[i]))
        ref_wxyz = np.array([ref[3], ref[0], ref[1], ref[2]])
        assert min(np.abs(got[i] - ref_wxyz).max(), np.abs(got[i] + ref_wxyz).max()) < 1e-9


def test_material_colours_inline_reference_and_unknown() -> None:
    robot = Robot("r", materials=(Material("red", (1.0, 0.0, 0.0, 1.0)),))
    assert material_rgba(Material("red"), robot) == (1.0, 0.0, 0.0, 1.0)
    assert material_rgba(Material("x", (0.0, 1.0, 0.0, 0.5)), robot) == (0.0, 1.0, 0.0, 0.5)
    assert material_rgba(Material("nope"), robot) is None
    assert material_rgba(None, robot) is None


def test_meshes_stl_dae_obj_load_and_are_cached(tmp_path: Path) -> None:
    robots = example_robot_data_dir()
    stl = robots / "talos_data/meshes/v2/knee_lo_res.stl"
    dae = robots / "a1_description/meshes/trunk.dae"
    objs = sorted(robots.rglob("*.obj"))
    assert objs, "example-robot-data ships OBJ meshes"
    for path in (stl, dae, objs[0]):
        parts = load_mesh_file(path)
        assert parts and all(p.faces.shape[1] == 3 and p.vertices.shape[1] == 3 for p in parts)
        assert not parts[0].vertices.flags.writeable
    assert load_mesh_file(dae)[0].rgba is not None  # the DAE's own material colour
    cache = MeshCache()
    copy = tmp_path / "knee.stl"
    copy.write_bytes(stl.read_bytes())
    first = cache.get(copy)
    assert cache.get(copy) is first and cache.loads == 1
    copy.write_bytes(stl.read_bytes() + b"")  # same bytes: new mtime only if the clock moved
    time.sleep(0.01)
    copy.touch()
    cache.get(copy)
    assert cache.loads == 2


def test_mesh_uris_resolve_and_escapes_are_refused() -> None:
    share = example_robot_data_dir().parents[1]
    index = PackageIndex(packages={"example-robot-data": share / "example-robot-data"})
    triple = "package:///example-robot-data/robots/talos_data/meshes/v2/knee_lo_res.stl"
    assert resolve_mesh_uri(index, triple, Path("/")).is_file()
    with pytest.raises(PathEscapeError):
        resolve_mesh_uri(index, "package://example-robot-data/../../../etc/passwd", Path("/"))
    assert resolve_mesh_uri(index, "m/a.stl", Path("/base")) == Path("/base/m/a.stl")


def test_floating_and_planar_joint_transforms() -> None:
    origin = Origin(xyz_m=(1.0, 0.0, 0.0))
    floating = Joint("f", JointType.FLOATING, "a", "b", origin=origin)
    T = body_transform(floating, BodyPose((0.0, 2.0, 0.0), (0.0, 0.0, math.pi / 2)))
    np.testing.assert_allclose(T[:3, 3], (1.0, 2.0, 0.0), atol=1e-12)
    np.testing.assert_allclose(T[:3, 0], (0.0, 1.0, 0.0), atol=1e-12)
    planar = Joint("p", JointType.PLANAR, "a", "b", axis=(0.0, 0.0, 1.0))
    T = body_transform(planar, BodyPose((0.3, 0.4, 0.0), (0.0, 0.0, 0.5)))
    assert T[2, 3] == pytest.approx(0.0) and np.hypot(T[0, 3], T[1, 3]) == pytest.approx(0.5)
    np.testing.assert_allclose(T[:3, 2], (0.0, 0.0, 1.0), atol=1e-12)


def test_examples_parse_for_the_viewer() -> None:
    # The robots the docs and the tests view exist and parse.
    text = (EXAMPLES / "two_link_arm/urdf/two_link_arm.urdf").read_text()
    assert read_urdf(text).robot.links


def test_missing_viser_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    import sys

    from robomodel.errors import MissingDependencyError
    from robomodel.viewer._deps import import_trimesh, import_viser

    monkeypatch.setitem(sys.modules, "viser", None)
    monkeypatch.setitem(sys.modules, "trimesh", None)
    for load in (import_viser, import_trimesh):
        with pytest.raises(MissingDependencyError, match=r"robomodel\[viewer\]"):
            load()


@pytest.mark.parametrize(
    "module_name",
    [
        "robomodel.viewer",
        "robomodel.viewer.app",
        "robomodel.viewer.scene",
        "robomodel.viewer.session",
        "robomodel.viewer.link_poses",
        "robomodel.viewer.pose_messages",
        "robomodel.viewer.meshes",
        "robomodel.viewer.joint_panel",
        "robomodel.viewer.tf_display",
        "robomodel.viewer.options_panel",
        "robomodel.viewer.status",
        "robomodel.viewer.tools",
        "robomodel.viewer.tools.base",
        "robomodel.viewer.tools.expression",
        "robomodel.viewer.tools.field_path",
        "robomodel.viewer.displays.follow",
        "robomodel.viewer.displays.topic_qos",
        "robomodel.viewer.tools.panel",
        "robomodel.viewer.tools.params",
        "robomodel.viewer.tools.plot",
        "robomodel.viewer.tools.publisher",
        "robomodel.viewer.tools.steering",
    ],
)
def test_viewer_public_names_resolve(module_name: str) -> None:
    import importlib

    module = importlib.import_module(module_name)
    for name in module.__all__:
        assert getattr(module, name) is not None, name


def test_importing_the_viewer_loads_neither_viser_nor_trimesh() -> None:
    import subprocess
    import sys

    code = "import sys, robomodel.viewer, robomodel.viewer.tools, robomodel.cli.main as m; "
    code += "m.build_parser(); "
    code += "print('viser' in sys.modules, 'trimesh' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"]


def test_a_viewer_of_a_robot_without_mesh_files_loads_no_trimesh() -> None:
    """trimesh (with scipy, networkx and shapely) is about half of a viewer's start-up: a robot of
    boxes, cylinders and spheres, with its TF axes drawn, is shown without it."""
    import subprocess
    import sys

    code = (
        "import sys, time\n"
        "from robomodel.viewer import RobotSource, Viewer, ViewerOptions\n"
        f"viewer = Viewer(ViewerOptions(sources=(RobotSource({str(PLANAR)!r}),), port=0))\n"
        "viewer.start()\n"
        "try:\n"
        "    nodes = viewer.server.scene._handle_from_node_name\n"
        f"    deadline = time.monotonic() + {scaled(30)}\n"
        "    while '/displays/TF/axes/x' not in nodes and time.monotonic() < deadline:\n"
        "        time.sleep(0.05)\n"
        "    print('/displays/TF/axes/x' in nodes, 'trimesh' in sys.modules)\n"
        "finally:\n"
        "    viewer.close()\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["True", "False"], out.stderr


def test_set_poses_sends_only_the_changed_orientation_or_position() -> None:
    """A link that only turns sends one message, not two; unchanged links none."""
    import viser

    from robomodel.viewer.scene import RobotModelDisplay

    robot = read_urdf(
        '<robot name="r"><link name="a"/><link name="b"/><link name="c"/>'
        '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>'
        '<joint name="k" type="fixed"><parent link="b"/><child link="c"/></joint></robot>'
    ).robot
    server = viser.ViserServer(host="127.0.0.1", port=0, verbose=False)
    try:
        display = RobotModelDisplay(
            server.scene,
            "/robots/0",
            robot,
            index=PackageIndex(),
            base_dir=Path.cwd(),
            meshes=MeshCache(),
        )
        display.build()
        sent: list[tuple[str, str]] = []
        queue = server.scene._queue_scene_message

        def record(message: object) -> None:
            wire = message.as_serializable_dict()  # type: ignore[attr-defined]
            sent.append((wire["type"], wire["name"]))
            queue(message)  # type: ignore[arg-type]

        server.scene._queue_scene_message = record  # type: ignore[method-assign]
        wxyz = np.tile([1.0, 0.0, 0.0, 0.0], (3, 1))
        xyz = np.zeros((3, 3))
        visible = np.ones(3, dtype=bool)
        assert display.set_poses(wxyz, xyz, visible) == 3  # first time: everything
        assert len([m for m in sent if m[0] == "SetOrientationMessage"]) == 3
        sent.clear()
        turned = wxyz.copy()
        turned[1] = [math.cos(0.2), 0.0, 0.0, math.sin(0.2)]
        shifted = xyz.copy()
        shifted[2] = [0.0, 0.0, 0.5]
        assert display.set_poses(turned, shifted, visible) == 2
        names = {display._links[i]._impl.name for i in range(3)}
        assert sent == [
            ("SetOrientationMessage", f"/robots/0/l{robot.link_names.index('b')}"),
            ("SetPositionMessage", f"/robots/0/l{robot.link_names.index('c')}"),
        ]
        assert len(names) == 3
        sent.clear()
        assert display.set_poses(turned, shifted, visible) == 0
        assert sent == []
    finally:
        server.stop()


def test_pose_messages_are_what_viser_sends_for_its_own() -> None:
    """The quickly serialised pose messages put viser's bytes on the wire."""
    import msgspec
    from viser import _messages

    from robomodel.viewer.pose_messages import pose_message_types

    types = pose_message_types()
    assert types is not None  # this viser (1.1) has the message layout they rely on
    rng = np.random.default_rng(3)
    pairs = [
        (types.orientation, _messages.SetOrientationMessage, 4),
        (types.position, _messages.SetPositionMessage, 3),
    ]
    for fast, base, n in pairs:
        for k in range(20):
            value = tuple(rng.normal(size=n).tolist())
            ours, theirs = fast(f"/robots/0/l{k}", value), base(f"/robots/0/l{k}", value)
            ours.owner = theirs.owner = f"owner-{k}"
            wire = ours.as_serializable_dict()
            assert wire["type"] == base.__name__
            assert msgspec.msgpack.encode(wire) == msgspec.msgpack.encode(
                theirs.as_serializable_dict()
            )
            # viser coalesces by these keys: a fast message replaces viser's own and back
            assert ours.redundancy_key() == theirs.redundancy_key()
            assert ours.entity_state_key() == theirs.entity_state_key()
    # Clients' messages are looked up by type name: the subclasses must not shadow viser's.
    table = _messages.Message._subclass_from_type_string()
    assert table["SetOrientationMessage"] is _messages.SetOrientationMessage


def test_pose_messages_fall_back_when_viser_serialises_differently(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from viser import _messages

    from robomodel.viewer import pose_messages

    def renamed(self: object, binary_buffers: object = None) -> dict[str, object]:
        return {"type": type(self).__name__, "node": getattr(self, "name", None)}

    pose_messages.pose_message_types.cache_clear()
    monkeypatch.setattr(_messages.Message, "as_serializable_dict", renamed)
    try:
        assert pose_messages.pose_message_types() is None
    finally:
        pose_messages.pose_message_types.cache_clear()


def test_next_big_update_waits_for_pages_to_be_sent_the_previous_one() -> None:
    """A new update would replace pose messages still waiting to be sent."""
    from types import SimpleNamespace

    from robomodel.viewer.app import Viewer

    buffer = SimpleNamespace(generator_cursors={}, message_counter=300, max_window_size=128)
    viewer = SimpleNamespace(
        _broadcast_buffer=lambda: buffer, _last_push_ids=(100, 299), _last_push_s=10.0
    )
    behind = Viewer._page_behind
    assert not behind(viewer, 10.1)  # type: ignore[arg-type]  # no page
    buffer.generator_cursors = {1: 299, 2: 200}
    assert behind(viewer, 10.1)  # type: ignore[arg-type]  # page 2 has half of it
    assert not behind(viewer, 10.6)  # type: ignore[arg-type]  # waited 0.5 s
    buffer.generator_cursors = {1: 299, 2: 299}
    assert not behind(viewer, 10.1)  # type: ignore[arg-type]
    viewer._last_push_ids = (250, 299)  # fits in one frame: sent whole, not waited for
    buffer.generator_cursors = {1: 0}
    assert not behind(viewer, 10.1)  # type: ignore[arg-type]
    viewer._last_push_ids = None
    assert not behind(viewer, 10.1)  # type: ignore[arg-type]  # nothing pushed yet


def test_view_sources_take_the_prefixes_in_order_files_then_topics() -> None:
    """``--prefix`` gives each FILE its frame_prefix, then each ``--description-topic``'s robot
    its TF Prefix; no FILE and no topic is RViz's empty start."""
    from robomodel.cli.main import build_parser
    from robomodel.cli.view import _checked_inputs, _robot_sources

    def sources(*argv: str) -> list[tuple[str, str, str | None]]:
        args = build_parser().parse_args(["view", *argv])
        return [(s.path, s.prefix, s.topic) for s in _robot_sources(args, *_checked_inputs(args))]

    assert sources() == []
    assert sources("--bus", "zenoh", "--joint-states", "external") == []
    assert sources("a.urdf", "--description-topic", "r1/robot_description",
                   "--description-topic", "/r2/robot_description", "--bus", "zenoh",
                   "--prefix", "a/", "--prefix", "r1/", "--prefix", "r2/") == [
        ("a.urdf", "a/", None), ("", "r1/", "/r1/robot_description"),
        ("", "r2/", "/r2/robot_description")]  # fmt: skip


def test_view_without_a_file_serves_an_empty_page_and_says_how_a_robot_comes(
    cli: Callable[..., ToolResult],
) -> None:
    result = cli("view", "--no-browser", "--port", "0", "--duration", "0.5")
    assert result.code == 0, result.err
    assert "serving http://" in result.out
    assert "no FILE: the page starts with no robot; no other process can describe one on --bus inproc" in result.err  # fmt: skip
