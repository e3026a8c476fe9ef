"""robomodel's roslaunch language against Debian's roslaunch 1.16 (the reference).

For every corpus launch file (and every ROS 1 launch file of examples/), ``--dump-params``,
``--nodes``, ``--args NODE`` for every node, ``--files`` and ``--ros-args`` are produced by
Debian's roslaunch and by robomodel (``robomodel.launch.ros1``), and compared: the parameter
tree as parsed YAML (``robot_description``-like XML values as canonical XML; ``$(anon)`` names
normalised), the rest as text.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path
from typing import Any

import pytest
import yaml
from lxml import etree

from robomodel.description.packages import PackageIndex
from robomodel.launch.model import LaunchError
from robomodel.launch.packages import SHARE
from robomodel.launch.ros1 import (
    format_dump_params,
    format_files,
    format_node_args,
    format_nodes,
    format_ros_args,
    load_launch,
)
from tests.conftest import EXAMPLES
from tests.launch.ros1.conftest import CORPUS, reference_env, roslaunch, roslaunch_many

CASES: list[tuple[str, dict[str, str]]] = [
    ("params.launch", {}),
    ("names.launch", {}),
    ("names.launch", {"robot": "other"}),
    ("args.launch", {"model": "m1"}),
    ("args.launch", {"model": "m2", "use_gui": "true", "count": "1"}),
    ("display.launch", {}),
]
EXAMPLE_LAUNCHES = sorted(EXAMPLES.glob("*/launch/*.launch"))


def _canonical(value: Any) -> Any:
    if isinstance(value, str) and value.lstrip().startswith("<") and "<robot" in value:
        parser = etree.XMLParser(remove_blank_text=True, remove_comments=True)
        return etree.tostring(etree.fromstring(value.encode(), parser), method="c14n")
    if isinstance(value, str):
        return re.sub(r"_[\w]+_\d+_\d+", "_ANON", value)
    return value


def _params(text: str) -> dict[str, Any]:
    data = yaml.safe_load(text) or {}
    return {key: _canonical(value) for key, value in data.items()}


def _ours(path: Path, args: dict[str, str], package_paths: list[Path], home: Path) -> Any:
    env = reference_env(package_paths, home)
    index = PackageIndex(package_paths=package_paths, use_environment=False)
    return load_launch(path, args=args, packages=index, environ=env), index, env


def _compare(path: Path, args: dict[str, str], package_paths: list[Path], home: Path) -> None:
    env = reference_env(package_paths, home)
    argv = [f"{k}:={v}" for k, v in args.items()]
    launch, index, env = _ours(path, args, package_paths, home)
    specs = (*launch.nodes, *launch.tests)
    modes = [["--dump-params"], ["--nodes"], ["--files"], ["--ros-args"]]
    modes += [["--args", spec.fqn] for spec in specs]
    dump, nodes, files, ros_args, *node_args = roslaunch_many(
        [[*mode, str(path), *argv] for mode in modes], env, path.parent
    )
    assert dump.returncode == 0 and "Unable to load" not in dump.stdout + dump.stderr, dump.stderr
    assert _params(format_dump_params(launch)) == _params(dump.stdout)
    assert format_nodes(launch).split() == nodes.stdout.split()
    assert sorted(format_files(launch).split()) == sorted(files.stdout.split())
    assert format_ros_args(launch) == ros_args.stdout
    for spec, ref in zip(specs, node_args, strict=True):
        found = _rospack_find(spec.package, env)
        if ref.returncode != 0 or found is None:  # the reference cannot find the node either
            assert found is None or "Cannot locate node" in ref.stdout + ref.stderr
            with pytest.raises(LaunchError):
                format_node_args(launch, spec.fqn, packages=index, environ=env)
            continue
        with_system = PackageIndex(
            package_paths=package_paths, packages={spec.package: found}, use_environment=False
        )
        ours = format_node_args(launch, spec.fqn, packages=with_system, environ=env)
        assert re.sub(r"_ANON", "", ours) == re.sub(r"_ANON", "", ref.stdout), spec.fqn


def _rospack_find(package: str, env: dict[str, str]) -> str | None:
    """Where Debian's rospack finds ``package`` (its paths include /usr/share)."""
    run = subprocess.run(
        ["/usr/bin/rospack", "find", package], capture_output=True, text=True, env=env
    )
    return run.stdout.strip() if run.returncode == 0 else None


@pytest.mark.parametrize(("name", "args"), CASES, ids=[f"{n}-{len(a)}" for n, a in CASES])
def test_corpus_matches_roslaunch(
    workspace: Path, tmp_path: Path, name: str, args: dict[str, str]
) -> None:
    path = workspace / "demo_pkg" / "launch" / name
    _compare(path, args, [workspace], tmp_path / "home")


@pytest.mark.parametrize("path", EXAMPLE_LAUNCHES, ids=[p.name for p in EXAMPLE_LAUNCHES])
def test_examples_match_roslaunch(workspace: Path, tmp_path: Path, path: Path) -> None:
    # The examples name $(find xacro) etc.: our built-in packages serve both sides.
    _compare(path, {}, [EXAMPLES, workspace / "xacro", SHARE], tmp_path / "home")


def test_corpus_is_complete() -> None:
    """Every element, attribute and substitution of roslaunch's XML format appears in the corpus."""
    launches = sorted((CORPUS / "demo_pkg" / "launch").glob("*.launch"))
    text = "".join(p.read_text() for p in launches)
    for needle in (
        "<arg ", "default=", "value=", "doc=", "<param ", "type=", "textfile=", "binfile=",
        "command=", "<rosparam", 'command="load"', 'command="dump"', 'command="delete"',
        "subst_value=", "<node ", "ns=", "args=", "output=", "required=", "respawn=",
        "respawn_delay=", "launch-prefix=", "clear_params=", "cwd=", "<remap ", "<env ",
        "<include ", "pass_all_args=", "<group ", "<machine ", "<test ", "if=", "unless=",
        "$(find ", "$(arg ", "$(env ", "$(optenv ", "$(dirname)", "$(eval ", "~",
    ):  # fmt: skip
        assert needle in text, needle


def test_binfile_param_is_bytes_and_dumps_where_roslaunch_crashes(
    workspace: Path, tmp_path: Path
) -> None:
    from robomodel.launch.ros1.params import Binary

    path = workspace / "demo_pkg" / "launch" / "binfile.launch"
    env = reference_env([workspace], tmp_path / "home")
    ref = roslaunch(["--dump-params", str(path)], env, path.parent)
    assert "RepresenterError" in ref.stderr  # the reference bug robomodel fixes
    launch, _, _ = _ours(path, {}, [workspace], tmp_path / "home")
    blob = (workspace / "demo_pkg" / "config" / "blob.bin").read_bytes()
    assert launch.params["/blob"] == Binary(blob)
    assert yaml.safe_load(format_dump_params(launch)) == {"/blob": blob}
