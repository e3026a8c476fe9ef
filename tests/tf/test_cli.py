"""The tf, frames, fk and ik commands."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from tests.conftest import ToolResult, example_robot_data_dir

Cli = Callable[..., ToolResult]
UR5 = str(example_robot_data_dir() / "ur_description/urdf/ur5_robot.urdf")

# robot_state_publisher's test URDF (two_links_moving_joint.urdf), plus a limit window that
# excludes 0 and a prismatic joint, to exercise joint_state_publisher's defaults.
TWO_LINKS = """<robot name="two">
  <link name="link1"/><link name="link2"/><link name="link3"/>
  <joint name="joint1" type="continuous"><parent link="link1"/><child link="link2"/>
    <origin xyz="5 0 0" rpy="0 0 1.57"/><axis xyz="0 0 1"/></joint>
  <joint name="slide" type="prismatic"><parent link="link2"/><child link="link3"/>
    <axis xyz="1 0 0"/><limit lower="0.2" upper="0.4" effort="1" velocity="1"/></joint>
</robot>"""


@pytest.fixture
def two_links(tmp_path: Path) -> str:
    path = tmp_path / "two.urdf"
    path.write_text(TWO_LINKS)
    return str(path)


def test_tf_prints_tf2_echo_block(cli: Cli, two_links: str) -> None:
    result = cli("tf", two_links, "link1", "link3", "--joint", "joint1=3.141592653589793")
    assert result.code == 0, result.err
    # joint1 = pi on top of yaw 1.57; the slide starts mid-window (0.3), as joint_state_publisher.
    yaw = 1.57 + math.pi - 2 * math.pi
    x = 5 + 0.3 * math.cos(yaw)
    y = 0.3 * math.sin(yaw)
    c, s = math.cos(yaw), math.sin(yaw)
    expected = (
        "At time 0.0\n"
        f"- Translation: [{x:.3f}, {y:.3f}, 0.000]\n"
        f"- Rotation: in Quaternion [0.000, 0.000, {math.sin(yaw / 2):.3f}, {math.cos(yaw / 2):.3f}]\n"
        f"- Rotation: in RPY (radian) [0.000, 0.000, {yaw:.3f}]\n"
        f"- Rotation: in RPY (degree) [0.000, 0.000, {math.degrees(yaw):.3f}]\n"
        "- Matrix:\n"
        f" {c:6.3f} {-s:6.3f}  0.000 {x:6.3f}\n"
        f" {s:6.3f} {c:6.3f} -0.000 {y:6.3f}\n"  # yz - wx = (0 * zs) - w * 0 = -0.0
        " -0.000  0.000  1.000  0.000\n"  # xz - wy = -0.0 likewise
        "  0.000  0.000  0.000  1.000\n"
    )
    # Signed zeros follow tf2's arithmetic (pitch = -asin(xz - wy)): here xz = 0 * z < 0 gives
    # -0.0 and so pitch +0.0; tf2_echo shows "-0.000" when z > 0 (as in the ROS tutorials).
    assert result.out == expected


def test_tf_argument_order_is_tf2_echos(cli: Cli, two_links: str) -> None:
    # tf2_echo A B prints the pose of B in A: swapping the frames inverts the transform.
    forward = cli("tf", two_links, "link1", "link2").out
    backward = cli("tf", two_links, "link2", "link1").out
    assert "- Translation: [5.000, 0.000, 0.000]" in forward
    assert "- Translation: [-0.004, 5.000, 0.000]" in backward


def test_tf_unknown_frame(cli: Cli, two_links: str) -> None:
    result = cli("tf", two_links, "link1", "link9")
    assert result.code == 2
    assert '"link9" passed to lookupTransform argument source_frame does not exist.' in result.err
    assert "Frame link2 exists with parent link1." in result.err


def test_tf_frame_prefix_and_bad_joint(cli: Cli, two_links: str) -> None:
    ok = cli("tf", two_links, "r1/link1", "r1/link2", "--frame-prefix", "r1/")
    assert ok.code == 0 and "[5.000, 0.000, 0.000]" in ok.out
    bad = cli("tf", two_links, "link1", "link2", "--joint", "jiont1=1")
    assert bad.code == 2 and "did you mean 'joint1'" in bad.err
    nan = cli("tf", two_links, "link1", "link2", "--joint", "joint1=nan")
    assert nan.code == 2 and "finite" in nan.err


def test_frames_gv(cli: Cli, two_links: str, tmp_path: Path) -> None:
    out = tmp_path / "frames.gv"
    result = cli("frames", two_links, "-o", str(out))
    assert result.code == 0, result.err
    text = out.read_text()
    assert text.startswith(
        'digraph G {\n"link1" -> "link2"[label=" Broadcaster: default_authority\\n'
    )
    assert "Average rate: 10000.0\\nBuffer length: 0.0\\nMost recent transform: 0.0\\n" in text
    assert 'label ="view_frames Result";' in text and text.endswith('}->"link1";\n}')


def test_frames_svg(cli: Cli, two_links: str, tmp_path: Path) -> None:
    out = tmp_path / "frames.svg"
    assert cli("frames", two_links, "-o", str(out)).code == 0
    assert "<svg" in out.read_text()


def test_fk_json(cli: Cli) -> None:
    result = cli("fk", UR5, "--joint", "elbow_joint=0.5", "--link", "tool0", "--json")
    assert result.code == 0, result.err
    doc = json.loads(result.out)
    assert doc["root"] == "world" and list(doc["links"]) == ["tool0"]
    assert doc["joints"]["elbow_joint"] == 0.5
    T = np.array(doc["links"]["tool0"]["matrix"])
    np.testing.assert_allclose(T[:3, 3], doc["links"]["tool0"]["xyz"])
    text = cli("fk", UR5)
    assert text.code == 0 and text.out.count("\n") == 1 + 11


def test_ik_numeric_analytic_and_unreachable(cli: Cli) -> None:
    target = ["--xyz", "0.4", "0.2", "0.3", "--rpy", "3.14", "0", "0"]
    num = cli("ik", UR5, "--link", "tool0", *target, "--json")
    assert num.code == 0, num.err
    doc = json.loads(num.out)
    assert doc["position_error_m"] <= 1e-6 and len(doc["solutions"]) == 1
    analytic = json.loads(cli("ik", UR5, "--link", "tool0", *target, "--all", "--json").out)
    assert analytic["analytic"] and 2 <= len(analytic["solutions"]) <= 8
    far = cli("ik", UR5, "--link", "tool0", "--xyz", "4", "0", "0")
    assert far.code == 1 and "cannot reach" in far.err
    far_all = cli(
        "ik", UR5, "--link", "tool0", "--xyz", "4", "0", "0", "--rpy", "0", "0", "0", "--all"
    )
    assert far_all.code == 1
    unknown = cli("ik", UR5, "--link", "tool9", "--xyz", "0", "0", "0")
    assert unknown.code == 2 and "did you mean 'tool0'" in unknown.err


def test_ik_all_on_a_non_ur_arm(cli: Cli) -> None:
    panda = str(example_robot_data_dir() / "panda_description/urdf/panda.urdf")
    result = cli(
        "ik",
        panda,
        "--link",
        "panda_hand",
        "--xyz",
        "0.3",
        "0",
        "0.5",
        "--rpy",
        "3.14",
        "0",
        "0",
        "--all",
    )
    assert result.code == 2 and "exactly 6 revolute" in result.err
