"""Every example expands byte-identically with the reference and passes urdfdom's check_urdf."""

from __future__ import annotations

import importlib.util
import shutil
import subprocess
from pathlib import Path
from types import ModuleType

import pytest

from robomodel import xacro as rx
from robomodel.description.packages import PackageIndex
from tests.xacro.conftest import EXAMPLES, REPO, example_index, reference_deps, reference_file

# (xacro file relative to examples/, mappings)
EXAMPLE_RUNS: list[tuple[str, dict[str, str]]] = [
    ("simplebot_description/urdf/simplebot.urdf.xacro", {}),
    ("simplebot_description/urdf/simplebot_lidar.urdf.xacro", {}),
    ("simplebot_description/urdf/simplebot_camera.urdf.xacro", {}),
    ("rrbot_description/urdf/rrbot.xacro", {}),
    ("ur5_description/urdf/ur5.urdf.xacro", {}),
    ("ur5_description/urdf/ur5.urdf.xacro", {"prefix": "left_"}),
    ("ur5_description/urdf/ur5_joint_limited_robot.urdf.xacro", {}),
    ("two_link_arm/urdf/two_link_arm.urdf.xacro", {}),
    ("two_link_arm/urdf/two_link_arm.urdf.xacro", {"links": "5"}),
    ("example_description/urdf/example.urdf.xacro", {}),
    ("example_description/urdf/example.urdf.xacro", {"robot_name": "turtle1"}),
]
IDS = [f"{p.split('/')[-1]}{'-' + '-'.join(m.values()) if m else ''}" for p, m in EXAMPLE_RUNS]


@pytest.mark.parametrize(("relative", "mappings"), EXAMPLE_RUNS, ids=IDS)
def test_example_is_byte_identical(relative: str, mappings: dict[str, str]) -> None:
    path = EXAMPLES / relative
    index = example_index()
    expected = reference_file(path, mappings, index)
    result = rx.expand(path, mappings=mappings, package_index=index)
    assert result.text == expected
    assert sorted(set(result.includes)) == sorted(set(reference_deps(path, index)))


@pytest.mark.parametrize(("relative", "mappings"), EXAMPLE_RUNS, ids=IDS)
def test_example_passes_check_urdf(relative: str, mappings: dict[str, str], tmp_path: Path) -> None:
    check_urdf = shutil.which("check_urdf")
    assert check_urdf is not None, "urdfdom's check_urdf is required (apt install liburdfdom-tools)"
    result = rx.expand(EXAMPLES / relative, mappings=mappings, package_index=example_index())
    out = tmp_path / "robot.urdf"
    out.write_text(result.text)
    proc = subprocess.run([check_urdf, str(out)], capture_output=True, text=True, check=False)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "Successfully Parsed XML" in proc.stdout


def test_ur5_kinematic_parameters() -> None:
    text = rx.expand(
        EXAMPLES / "ur5_description/urdf/ur5.urdf.xacro", package_index=example_index()
    ).text
    assert 'xyz="0.0 0.0 0.089159"' in text  # d1
    assert 'xyz="0.0 0.0 0.39225"' in text  # -a3
    assert 'value="8.393"' in text


def test_two_link_arm_recursion_makes_three_identical_links() -> None:
    text = rx.expand(EXAMPLES / "two_link_arm/urdf/two_link_arm.urdf.xacro").text
    assert [f'<link name="link{i}">' in text for i in (1, 2, 3, 4)] == [True, True, True, False]


def test_example_description_uses_yaml_units_and_prefix() -> None:
    text = rx.expand(
        EXAMPLES / "example_description/urdf/example.urdf.xacro",
        mappings={"robot_name": "r1"},
        package_index=example_index(),
    ).text
    assert 'lower="-3.141592653589793"' in text  # !degrees -180
    assert 'radius="0.02"' in text  # !millimeters 20
    assert '<link name="r1/base_link">' in text


def _bench_module() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_xacro", REPO / "bench" / "bench_xacro.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_synthetic_pr2_size_robot(tmp_path: Path) -> None:
    top = _bench_module().write_synthetic_robot(tmp_path)
    index = PackageIndex(package_paths=[tmp_path], use_environment=False)
    result = rx.expand(top, package_index=index)
    assert result.text == reference_file(top, index=index)
    assert len(result.text) >= 130_000 and result.text.count("<link ") >= 80
    assert len(result.includes) >= 5
