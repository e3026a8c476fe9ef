"""ROS package discovery and resource resolution."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from robomodel.description import _crawl
from robomodel.description.packages import PackageIndex, index_from_options, parse_package_option
from robomodel.errors import PackageNotFoundError, PathEscapeError, RobomodelError

# rospack's reading of a manifest's name, as a regular expression (what the crawl computes
# without importing ``re``, which would cost every Python start whose import the finder sees)
_NAME_RE = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")
_PIECES = st.sampled_from(
    [b"<name>", b"</name>", b"<", b">", b" ", b"\n", b"\t", b"a", b"b_c", b"<x/>", b"\xc3\xa9"]
)


@given(st.lists(_PIECES, max_size=14).map(b"".join))
def test_the_manifest_name_is_read_as_rospack_s_expression_reads_it(head: bytes) -> None:
    match = _NAME_RE.search(head)
    assert _crawl._name_in(head) == (match.group(1).decode("utf-8", "replace") if match else None)


def test_a_manifest_s_name_is_its_first_well_formed_name() -> None:
    assert _crawl._name_in(b"<name>a b</name><name>\n pkg \n</name>") == "pkg"
    assert _crawl._name_in(b"<name><x/></name>") is None
    assert _crawl._name_in(b"<name></name>") is None


def _package(root: Path, name: str, directory: str | None = None) -> Path:
    path = root / (directory or name)
    path.mkdir(parents=True)
    (path / "package.xml").write_text(
        f'<?xml version="1.0"?>\n<package format="3">\n  <name>{name}</name>\n</package>\n'
    )
    return path


def test_recursive_scan_uses_manifest_name_and_stops_at_packages(tmp_path: Path) -> None:
    a = _package(tmp_path / "ws" / "src", "alpha_description", "some_dir")
    _package(a / "nested", "hidden_inside")  # rospack does not descend into a package
    _package(tmp_path / "ws" / "src" / "deep" / "er", "beta")
    ignored = _package(tmp_path / "ws" / "src" / "skip", "gamma")
    (ignored.parent / "COLCON_IGNORE").write_text("")
    _package(tmp_path / "ws" / ".hidden", "delta")
    index = PackageIndex(package_paths=[tmp_path / "ws"], use_environment=False)
    assert index.names() == ("alpha_description", "beta")
    assert index.find("alpha_description") == a


def test_only_a_file_is_a_manifest_and_a_package_s_own_ignore_marker_does_not_hide_it(
    tmp_path: Path,
) -> None:
    """As rospack: a folder that holds a package.xml *file* is a package even with an ignore
    marker beside it (the marker hides the folders below), and a folder named package.xml is
    crawled into like any other."""
    kept = _package(tmp_path / "src", "epsilon")
    (kept / "CATKIN_IGNORE").write_text("")
    inside = _package(tmp_path / "src" / "odd" / "package.xml", "zeta")
    found: dict[str, str] = {}
    _crawl.scan_tree(str(tmp_path / "src"), found)
    assert found == {"epsilon": str(kept), "zeta": str(inside)}


def test_priority_explicit_then_paths_then_environment(tmp_path: Path) -> None:
    first = _package(tmp_path / "one", "pkg")
    second = _package(tmp_path / "two", "pkg")
    ament = tmp_path / "install"
    _package(ament / "share", "pkg")
    _package(ament / "share", "only_ament")
    env = {"ROS_PACKAGE_PATH": str(tmp_path / "two"), "AMENT_PREFIX_PATH": str(ament)}
    assert PackageIndex(package_paths=[tmp_path / "one"], environ=env).find("pkg") == first
    assert PackageIndex(environ=env).find("pkg") == second
    assert PackageIndex(environ=env).find("only_ament") == ament / "share" / "only_ament"
    explicit = tmp_path / "elsewhere"
    assert PackageIndex(packages={"pkg": explicit}, environ=env).find("pkg") == explicit


def test_resolve_uris(tmp_path: Path) -> None:
    pkg = _package(tmp_path, "robot_description")
    index = PackageIndex(package_paths=[tmp_path], use_environment=False)
    assert index.resolve("package://robot_description/meshes/a.stl") == pkg / "meshes" / "a.stl"
    assert index.resolve("file:///abs/m%20x.stl") == Path("/abs/m x.stl")
    assert index.resolve("meshes/a.stl", base_dir=pkg / "urdf") == pkg / "urdf" / "meshes" / "a.stl"
    assert index.resolve("../meshes/a.stl", base_dir=pkg / "urdf") == pkg / "meshes" / "a.stl"
    assert index.package_of(pkg / "urdf" / "x.urdf") is not None


@pytest.mark.parametrize(
    "uri",
    ["package://robot_description/../../etc/passwd", "package://robot_description/a/../../x"],
)
def test_escape_refused(tmp_path: Path, uri: str) -> None:
    _package(tmp_path, "robot_description")
    index = PackageIndex(package_paths=[tmp_path], use_environment=False)
    with pytest.raises(PathEscapeError) as info:
        index.resolve(uri)
    assert "escapes package 'robot_description'" in str(info.value)


def test_unknown_package_suggests_close_names(tmp_path: Path) -> None:
    _package(tmp_path, "robot_description")
    index = PackageIndex(package_paths=[tmp_path], use_environment=False)
    with pytest.raises(PackageNotFoundError) as info:
        index.find("robot_descriptoin")
    assert "did you mean 'robot_description'" in str(info.value)
    assert str(tmp_path) in str(info.value)
    with pytest.raises(PackageNotFoundError, match="no package paths given"):
        PackageIndex(use_environment=False).find("x")


def test_options(tmp_path: Path) -> None:
    assert parse_package_option("a=/x") == ("a", Path("/x"))
    with pytest.raises(RobomodelError, match="NAME=DIR"):
        parse_package_option("nodir")
    index = index_from_options([], [f"custom={tmp_path}"])
    assert index.find("custom") == tmp_path


def test_workspace_of_the_input_is_searched_last(tmp_path: Path) -> None:
    ws = tmp_path / "ws" / "src"
    own = _package(ws, "robot_description")
    sibling = _package(ws, "robot_meshes")
    (own / "urdf").mkdir()
    urdf = own / "urdf" / "robot.urdf.xacro"
    urdf.write_text("<robot/>")
    elsewhere = _package(tmp_path / "other", "robot_meshes")
    index = PackageIndex(use_environment=False).with_workspace_of(urdf)
    assert index.find("robot_description") == own
    assert index.find("robot_meshes") == sibling
    # Explicit paths still win over the input's workspace.
    explicit = PackageIndex(package_paths=[tmp_path / "other"], use_environment=False)
    assert explicit.with_workspace_of(urdf).find("robot_meshes") == elsewhere
    assert PackageIndex(use_environment=False).with_workspace_of(tmp_path / "x.urdf").names() == ()
