"""Every file a user names is read through one bounded reader:
device files, FIFOs, directories and files over 64 MiB are refused with the file named; bytes
that are not UTF-8 are an error at their line and column, not a UnicodeDecodeError traceback."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

from robomodel._files import MAX_FILE_BYTES, UserFileError, read_user_bytes, read_user_text
from tests.conftest import ROBOMODEL
from tests.timing import scaled


@pytest.fixture
def fifo(tmp_path: Path) -> Path:
    path = tmp_path / "pipe.urdf"
    os.mkfifo(path)
    return path


def test_regular_files_are_read(tmp_path: Path) -> None:
    path = tmp_path / "a.txt"
    path.write_bytes("läuft\n".encode())
    assert read_user_bytes(path) == "läuft\n".encode()
    assert read_user_text(path) == "läuft\n"


@pytest.mark.parametrize(
    ("name", "kind"), [("/dev/zero", "a character device"), ("/tmp", "a directory")]
)
def test_devices_and_directories_are_refused(name: str, kind: str) -> None:
    with pytest.raises(UserFileError, match=f"{name}: cannot read launch file: it is {kind}"):
        read_user_bytes(name, what="launch file")


def test_a_fifo_is_refused_without_blocking(fifo: Path) -> None:
    with pytest.raises(UserFileError, match="named pipe"):
        read_user_bytes(fifo)


def test_large_files_are_refused_before_reading(tmp_path: Path) -> None:
    path = tmp_path / "big.yaml"
    with path.open("wb") as handle:  # sparse: no disk space used
        handle.truncate(MAX_FILE_BYTES + 1)
    with pytest.raises(UserFileError, match="files over 64 MiB are refused"):
        read_user_bytes(path)
    small = tmp_path / "small.yaml"
    small.write_bytes(b"x" * 11)
    with pytest.raises(UserFileError, match="over 0 MiB"):
        read_user_bytes(small, limit=10)


def test_missing_files_keep_their_errno(tmp_path: Path) -> None:
    with pytest.raises(UserFileError, match="No such file") as caught:
        read_user_bytes(tmp_path / "nope.xacro")
    assert caught.value.errno == 2


def test_non_utf8_is_located(tmp_path: Path) -> None:
    path = tmp_path / "params.yaml"
    path.write_bytes(b"a: 1\nbb: \xff\xfe\n")
    with pytest.raises(UserFileError) as caught:
        read_user_text(path)
    assert (caught.value.line, caught.value.column) == (2, 5)
    assert str(caught.value).startswith(f"{path}:2:5: not UTF-8 text: byte 0xff")


def _run(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*ROBOMODEL, *args], capture_output=True, text=True, timeout=scaled(60), cwd=cwd
    )


@pytest.mark.parametrize("verb", ["xacro", "check"])
def test_cli_refuses_dev_zero(verb: str) -> None:
    done = _run(verb, "/dev/zero")
    assert done.returncode == 2
    assert "/dev/zero" in done.stderr and "character device" in done.stderr
    assert "Traceback" not in done.stderr


def test_xacro_include_and_load_yaml_of_dev_zero(tmp_path: Path) -> None:
    include = tmp_path / "inc.xacro"
    include.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="/dev/zero"/>\n</robot>\n'
    )
    done = _run("xacro", str(include))
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert f"{include}:2:" in done.stderr and "/dev/zero" in done.stderr
    yaml_user = tmp_path / "yaml.xacro"
    yaml_user.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="p" value="${xacro.load_yaml(\'/dev/zero\')}"/>\n'
        '  <link name="${p}"/>\n</robot>\n'
    )
    done = _run("xacro", str(yaml_user))
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert "load_yaml('/dev/zero')" in done.stderr and "character device" in done.stderr


def test_mesh_loaders_refuse_device_files() -> None:
    pytest.importorskip("trimesh")
    from robomodel.sim.build.geoms import _load
    from robomodel.sim.exceptions import SimulationError
    from robomodel.viewer.meshes import MeshLoadError, load_mesh_file

    with pytest.raises(MeshLoadError, match="character device"):
        load_mesh_file(Path("/dev/zero"))
    with pytest.raises(SimulationError, match="/dev/zero: cannot read mesh file"):
        _load("/dev/zero", "link 'base'")
