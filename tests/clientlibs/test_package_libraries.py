"""ament_index_python, rospkg and roslib over robomodel's package discovery: an installed ament
prefix, a source folder on ROS_PACKAGE_PATH and the working folder's workspace src/."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from robomodel.clientlibs import ament_index_python as ament
from robomodel.clientlibs import roslib, rospkg
from robomodel.clientlibs.roslib import message as roslib_message
from robomodel.clientlibs.roslib import packages as roslib_packages


def _package(folder: Path, name: str) -> Path:
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(f"<package format='3'><name>{name}</name></package>")
    return folder


@pytest.fixture
def places(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> dict[str, Path]:
    prefix = tmp_path / "install"
    marker = prefix / "share" / "ament_index" / "resource_index" / "packages"
    marker.mkdir(parents=True)
    (marker / "installed_pkg").write_text("")
    (prefix / "share" / "installed_pkg").mkdir()
    plugins = prefix / "share" / "ament_index" / "resource_index" / "rviz_plugins"
    plugins.mkdir()
    (plugins / "installed_pkg").write_text("plugin.xml\n")
    source = _package(tmp_path / "ros1" / "stack" / "source_pkg", "source_pkg")
    workspace = tmp_path / "ws"
    own = _package(workspace / "src" / "group" / "own_pkg", "own_pkg")
    (own / "src").mkdir()
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "ros1"))
    monkeypatch.setenv("ROBOMODEL_EXAMPLE_ROBOT_DATA", "0")
    monkeypatch.chdir(workspace)
    return {"prefix": prefix, "source": source, "own": own}


def test_ament_index_python(places: dict[str, Path]) -> None:
    prefix = places["prefix"]
    assert ament.get_package_prefix("installed_pkg") == str(prefix)
    assert ament.get_package_share_directory("installed_pkg") == str(
        prefix / "share" / "installed_pkg"
    )
    assert ament.get_package_share_path("own_pkg") == places["own"]
    assert ament.get_package_share_directory("source_pkg") == str(places["source"])
    with_prefixes = ament.get_packages_with_prefixes()
    assert with_prefixes["installed_pkg"] == str(prefix)
    assert {"own_pkg", "source_pkg"} <= set(with_prefixes)
    assert ament.get_search_paths() == [str(prefix)]
    assert ament.get_resource("rviz_plugins", "installed_pkg") == ("plugin.xml\n", str(prefix))
    assert ament.has_resource("rviz_plugins", "own_pkg") is None
    with pytest.raises(ament.PackageNotFoundError, match="did you mean 'own_pkg'") as caught:
        ament.get_package_share_directory("own_pkq")
    assert isinstance(caught.value, KeyError)


def test_rospkg_and_roslib(places: dict[str, Path], monkeypatch: pytest.MonkeyPatch) -> None:
    pack = rospkg.RosPack()
    assert pack.get_path("source_pkg") == str(places["source"])
    assert {"installed_pkg", "source_pkg", "own_pkg"} <= set(pack.list())
    assert rospkg.RosPack(ros_paths=[str(places["source"].parent)]).list() == ["source_pkg"]
    with pytest.raises(rospkg.ResourceNotFound, match="package 'nope' not found"):
        pack.get_path("nope")
    with pytest.raises(NotImplementedError, match="get_depends"):
        pack.get_depends("source_pkg")
    monkeypatch.setattr(sys, "path", list(sys.path))
    roslib.load_manifest("own_pkg")
    assert sys.path[0] == str(places["own"] / "src")
    with pytest.raises(rospkg.ResourceNotFound):
        roslib.load_manifest("nope")
    assert roslib_packages.get_pkg_dir("own_pkg") == str(places["own"])
    assert roslib_packages.get_pkg_dir("nope", required=False) is None
    assert roslib_message.get_message_class("std_msgs/String")._type == "std_msgs/String"
    assert roslib_message.get_message_class("std_msgs/Nope") is None
    assert roslib_message.get_service_class("std_srvs/SetBool")._request_class is not None
