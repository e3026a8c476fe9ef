"""The launch layer's bounds: substitution results, include fan-out,
device files and huge files, and ``<param command=>``'s time and output. Each is refused with
one clear line at file:line, exit code 2, no traceback."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from robomodel.launch.model import LaunchError
from robomodel.launch.ros1 import load_launch as load_ros1
from robomodel.launch.ros2 import load_launch as load_ros2
from tests.conftest import ROBOMODEL
from tests.timing import scaled


def _launch(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*ROBOMODEL, "launch", *args], capture_output=True, text=True, timeout=scaled(timeout)
    )


def _refused(done: subprocess.CompletedProcess[str], *needles: str) -> None:
    assert done.returncode == 2, done.stderr
    assert "Traceback" not in done.stderr
    for needle in needles:
        assert needle in done.stderr, done.stderr


# -- 1. substitution results -------------------------------------------------------------------
def test_a_doubling_roslaunch_arg_is_refused_at_the_step_that_passes_the_limit(
    tmp_path: Path,
) -> None:
    lines = ["<launch>", '<arg name="a0" default="xx"/>']
    lines += [f'<arg name="a{i}" default="$(arg a{i - 1})$(arg a{i - 1})"/>' for i in range(1, 40)]
    path = tmp_path / "double.launch"
    path.write_text("\n".join([*lines, '<param name="p" value="$(arg a39)"/>', "</launch>"]))
    with pytest.raises(LaunchError) as caught:
        load_ros1(path)
    # 2 * 2**22 = 8.4 M characters pass; a22 = 2 * 2**22 ... a23 would be 16.8 M: refused there
    assert caught.value.location.line == 25  # a23's line (line 1 is <launch>)
    assert "16,777,216 characters is over the 10,000,000-character limit" in str(caught.value)


@pytest.mark.parametrize("suffix", [".launch.xml", ".launch.yaml"])
def test_a_doubling_ros2_variable_is_refused(tmp_path: Path, suffix: str) -> None:
    path = tmp_path / f"double{suffix}"
    if suffix.endswith("xml"):
        lets = [f'<let name="a{i}" value="$(var a{i - 1})$(var a{i - 1})"/>' for i in range(1, 40)]
        path.write_text("<launch>\n<let name='a0' value='xx'/>\n" + "\n".join(lets) + "\n</launch>")
    else:
        lets = [
            f'- let: {{name: a{i}, value: "$(var a{i - 1})$(var a{i - 1})"}}' for i in range(1, 40)
        ]
        path.write_text("launch:\n- let: {name: a0, value: xx}\n" + "\n".join(lets) + "\n")
    with pytest.raises(LaunchError, match="over the 10,000,000-character limit"):
        load_ros2(path)


# -- 2. include fan-out ------------------------------------------------------------------------
def _fan_out(tmp_path: Path, suffix: str, body: str, depth: int = 16) -> Path:
    for level in range(depth + 1):
        child = f'<include file="{tmp_path}/f{level + 1}{suffix}"/>' * 2 if level < depth else ""
        (tmp_path / f"f{level}{suffix}").write_text(f"<launch>{body}{child}</launch>")
    return tmp_path / f"f0{suffix}"


def test_roslaunch_include_fan_out_is_refused(tmp_path: Path) -> None:
    top = _fan_out(tmp_path, ".launch", '<param name="x" value="1"/>')
    done = _launch(str(top), "--dump-params")
    _refused(done, "more than 200,000 units of work", "includes fan out exponentially")


def test_ros2_include_fan_out_is_refused(tmp_path: Path) -> None:
    top = _fan_out(tmp_path, ".launch.xml", '<let name="x" value="1"/>')
    done = _launch(str(top), "--show-args")
    _refused(done, "more than 200,000 units of work")


def test_every_example_launch_file_stays_under_the_work_bound() -> None:
    examples = Path(__file__).resolve().parents[2] / "examples"
    files = sorted(p for p in examples.rglob("*") if p.name.endswith((".launch", ".launch.py")))
    assert len(files) >= 10
    for path in files:
        loader = load_ros1 if path.suffix == ".launch" else load_ros2
        try:
            loader(path)
        except LaunchError as exc:  # a required arg is fine; the bound is not
            assert "units of work" not in str(exc), path


# -- 3. device files and huge files -----------------------------------------------------------
@pytest.mark.parametrize(
    ("tag", "what"),
    [
        ('<param name="t" textfile="/dev/zero"/>', "textfile"),
        ('<param name="b" binfile="/dev/zero"/>', "binfile"),
        ('<include file="/dev/zero"/>', "launch file"),
        ('<rosparam file="/dev/zero"/>', "rosparam file"),
    ],
)
def test_roslaunch_refuses_device_files(tmp_path: Path, tag: str, what: str) -> None:
    path = tmp_path / "dev.launch"
    path.write_text(f"<launch>\n  {tag}\n</launch>\n")
    done = _launch(str(path), "--dump-params")
    _refused(done, f"{path}:2:", f"/dev/zero: cannot read {what}: it is a character device")


def test_ros2_launch_refuses_device_files(tmp_path: Path) -> None:
    path = tmp_path / "dev.launch.xml"
    path.write_text(
        "<launch>\n  <let name='x' value='1'/>\n"
        '  <let name="c" value="$(file-content /dev/zero)"/>\n</launch>\n'
    )
    _refused(_launch(str(path), "--print"), "/dev/zero", "character device")
    # a node's parameter file that is not a regular file: skipped with launch_ros's warning
    path.write_text(
        "<launch>\n  <let name='x' value='1'/>\n"
        '  <node pkg="demo_nodes_cpp" exec="talker"><param from="/dev/zero"/></node>\n'
        "</launch>\n"
    )
    done = _launch(str(path), "--print")
    assert f"{path}:3: Parameter file path is not a file: /dev/zero" in done.stderr


def test_non_utf8_rosparam_file_is_an_error_at_its_byte(tmp_path: Path) -> None:
    params = tmp_path / "bad.yaml"
    params.write_bytes(b"gains:\n  p: \xff\xfe\n")
    path = tmp_path / "bad.launch"
    path.write_text(f'<launch>\n  <rosparam file="{params}"/>\n</launch>\n')
    done = _launch(str(path), "--dump-params")
    _refused(done, f"{params}:2:6: not UTF-8 text: byte 0xff")
    text = tmp_path / "bad.launch2"
    text.write_text(f'<launch>\n  <param name="t" textfile="{params}"/>\n</launch>\n')
    _refused(_launch(str(text), "--dump-params"), f"{params}:2:6: not UTF-8 text")


# -- 4. <param command=> -----------------------------------------------------------------------
def test_a_command_that_hangs_is_stopped_by_the_timeout(tmp_path: Path) -> None:
    path = tmp_path / "hang.launch"
    path.write_text('<launch>\n  <param name="c" command="sleep 100"/>\n</launch>\n')
    done = _launch(str(path), "--dump-params", "--command-timeout", "0.5")
    _refused(done, f"{path}:2:", "did not finish within 0.5 s", "--command-timeout")


def test_a_command_with_endless_output_is_capped(tmp_path: Path) -> None:
    path = tmp_path / "flood.launch"
    path.write_text('<launch>\n  <param name="c" command="cat /dev/zero"/>\n</launch>\n')
    _refused(_launch(str(path), "--dump-params"), "wrote more than 64 MiB of output")


def test_ros2_command_substitution_has_the_same_bounds(tmp_path: Path) -> None:
    path = tmp_path / "hang.launch.xml"
    path.write_text("<launch>\n  <let name='c' value=\"$(command 'sleep 100')\"/>\n</launch>\n")
    done = _launch(str(path), "--print", "--command-timeout", "0.5")
    _refused(done, "did not finish within 0.5 s")
