"""Textured DAE meshes are drawn with their textures, as RViz draws them, and every
mesh of a many-mesh robot is drawn (one failing mesh never stops the ones after it)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from robomodel.description import Mesh
from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from robomodel.viewer.meshes import MeshCache, load_mesh_file
from tests.conftest import example_robot_data_dir
from tests.viewer.conftest import (
    ViewerProcess,
    open_viewer,
    save_shot,
    settle,
    wait_for,
)
from tests.viewer.textured import write_textured_cube

ERD_SHARE = example_robot_data_dir().parents[1]  # .../share


def _textured_robot(tmp_path: Path) -> Path:
    write_textured_cube(tmp_path)
    # The URDF gives a green material: RViz keeps the mesh's own (textured) material.
    urdf = tmp_path / "cube.urdf"
    urdf.write_text(
        '<robot name="cube"><material name="green"><color rgba="0 1 0 1"/></material>'
        '<link name="base"><visual><geometry><mesh filename="cube.dae"/></geometry>'
        '<material name="green"/></visual></link></robot>'
    )
    return urdf


def test_a_textured_dae_keeps_its_texture(tmp_path: Path) -> None:
    parts = load_mesh_file(write_textured_cube(tmp_path))
    assert len(parts) == 1 and parts[0].glb is not None
    assert parts[0].glb[:4] == b"glTF"  # binary glTF, with the image inside
    assert b"image/png" in parts[0].glb
    untextured = ERD_SHARE / "example-robot-data/robots/a1_description/meshes/trunk.dae"
    assert load_mesh_file(untextured)[0].glb is None


def test_textured_dae_is_drawn_with_its_texture_in_the_browser(
    viewer: Callable[..., ViewerProcess], page: Any, tmp_path: Path
) -> None:
    view = viewer(_textured_robot(tmp_path))
    open_viewer(page, view.url)
    wait_for(lambda: page.get_by_text("OK").count(), what="the model to load")

    def shares(shot: np.ndarray) -> tuple[float, float, float]:
        """The shares of reddish, bluish and greenish pixels."""
        r, g, b = (shot[..., k].astype(int) for k in range(3))
        red = (r > 120) & (g < 80) & (b < 80)
        blue = (b > 120) & (r < 80) & (g < 80)
        green = (g > 120) & (r < 80) & (b < 80)
        return float(red.mean()), float(blue.mean()), float(green.mean())

    # The texture is decoded by the page after the mesh is drawn: on a busy machine two shots
    # of the untextured cube can agree (settled) before it is applied.
    _red, _blue, greenish = wait_for(
        lambda: s if min((s := shares(settle(page, 5)))[:2]) > 0.002 else None,
        what="the checker texture to be drawn",
    )
    save_shot(page, "textured_dae")
    assert greenish < 0.0005, "the URDF colour replaced the mesh's own texture"


@pytest.fixture
def started() -> Iterator[list[Viewer]]:
    viewers: list[Viewer] = []
    yield viewers
    for v in viewers:
        v.close()


def test_every_mesh_of_the_pr2_is_drawn(started: list[Viewer]) -> None:
    urdf = ERD_SHARE / "example-robot-data/robots/pr2_description/urdf/pr2.urdf"
    from robomodel.description.packages import PackageIndex

    index = PackageIndex(packages={"example-robot-data": ERD_SHARE / "example-robot-data"})
    v = Viewer(ViewerOptions(sources=(RobotSource(str(urdf)),), port=0, package_index=index))
    v.start()
    started.append(v)
    session = v.sessions[0]
    wait_for(lambda: session.display is not None and session.display.pending_meshes == 0, 60)
    display = session.display
    assert display is not None and not display.problems
    robot = session.robot
    assert robot is not None
    with_mesh = [
        i
        for i, link in enumerate(robot.links)
        if any(isinstance(v.geometry, Mesh) for v in link.visuals)
    ]
    drawn = {int(name.split("/l")[1].split("/")[0]) for name in display.mesh_nodes}
    assert set(with_mesh) <= drawn, [robot.links[i].name for i in set(with_mesh) - drawn]
    arm_links = [robot.links[i].name for i in with_mesh if robot.links[i].name.startswith("l_")]
    assert len(arm_links) >= 8  # both arms' meshes, not only the first shoulder


def test_one_failing_mesh_does_not_stop_the_others(
    started: list[Viewer], monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    write_textured_cube(tmp_path, "a")
    write_textured_cube(tmp_path, "b")
    write_textured_cube(tmp_path, "c")
    links = "".join(
        f'<link name="{n}"><visual><geometry><mesh filename="{n}.dae"/></geometry></visual></link>'
        for n in "abc"
    )
    joints = "".join(
        f'<joint name="j{n}" type="fixed"><parent link="a"/><child link="{n}"/></joint>'
        for n in "bc"
    )
    urdf = tmp_path / "three.urdf"
    urdf.write_text(f'<robot name="three">{links}{joints}</robot>')
    original = MeshCache.get

    def flaky(self: MeshCache, path: Path) -> Any:
        if Path(path).name == "b.dae":
            raise ValueError("a bug in a mesh library")
        return original(self, path)

    monkeypatch.setattr(MeshCache, "get", flaky)
    v = Viewer(ViewerOptions(sources=(RobotSource(str(urdf)),), port=0))
    v.start()
    started.append(v)
    session = v.sessions[0]
    wait_for(lambda: session.display is not None and session.display.pending_meshes == 0)
    display = session.display
    assert display is not None
    assert [p.link for p in display.problems] == ["b"]
    assert "ValueError: a bug in a mesh library" in display.problems[0].reason
    drawn_links = {
        display.link_names[int(n.split("/l")[1].split("/")[0])] for n in display.mesh_nodes
    }
    assert drawn_links == {"a", "c"}
