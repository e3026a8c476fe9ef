"""How the shim reaches what sits above it: the file loaders (a registry keyed by file type
that load_launch hands to the load) and the event dispatch (on the load's session)."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel.description.packages import PackageIndex
from robomodel.launch.model import LaunchError
from robomodel.launch.ros2 import load_launch
from robomodel.launch.ros2.frontend.xml_frontend import XML_LOADER
from robomodel.launch.ros2.loader import FILE_LOADERS
from robomodel.launch.ros2.shim.context import LaunchContext, Session, SubstitutionFailure
from robomodel.launch.ros2.shim.sources import LoaderRegistry, load_description_file, loader_scope

_EMPTY = PackageIndex(use_environment=False)


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


def test_an_include_of_an_unknown_file_type_names_the_types_read(tmp_path: Path) -> None:
    _write(tmp_path / "other.launch.txt", "")
    top = _write(
        tmp_path / "top.launch.xml",
        '<launch><include file="$(dirname)/other.launch.txt"/></launch>',
    )
    with pytest.raises(LaunchError, match=r"\(expected \.py, \.xml or \.yaml\)"):
        load_launch(top, packages=_EMPTY)


def test_the_registry_reads_only_the_types_it_holds(tmp_path: Path) -> None:
    xml = _write(tmp_path / "a.launch.xml", "<launch/>")
    python = _write(tmp_path / "a.launch.py", "")
    only_xml = LoaderRegistry([XML_LOADER])
    with loader_scope(only_xml):
        assert load_description_file(xml, "any").entities == []
        with pytest.raises(SubstitutionFailure, match=r"'.*a\.launch\.py' \(expected \.xml\)$"):
            load_description_file(python, "any")
        with pytest.raises(SubstitutionFailure, match=r"no loader for python launch files"):
            load_description_file(python, "python")
    assert FILE_LOADERS.kind_of(Path("x.YML")) == "yaml"


def test_loading_outside_load_launch_says_where_files_are_loaded(tmp_path: Path) -> None:
    xml = _write(tmp_path / "a.launch.xml", "<launch/>")
    with pytest.raises(SubstitutionFailure, match=r"loaded inside .*load_launch"):
        load_description_file(xml, "any")


def test_a_context_hands_event_handlers_to_its_loads_dispatch(tmp_path: Path) -> None:
    """OpaqueFunction code that registers a handler on the context, as upstream allows."""
    path = _write(
        tmp_path / "events.launch.py",
        "from launch import LaunchDescription\n"
        "from launch.actions import ExecuteProcess, OpaqueFunction, LogInfo\n"
        "from launch.event_handlers import OnProcessExit\n"
        "first = ExecuteProcess(cmd=['true'])\n"
        "def hook(context):\n"
        "    context.register_event_handler(\n"
        "        OnProcessExit(target_action=first, on_exit=[LogInfo(msg='after')]))\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([first, OpaqueFunction(function=hook)])\n",
    )
    launch = load_launch(path, packages=_EMPTY)
    assert [(s.kind, s.after_exit_of) for s in launch.steps] == [("process", None), ("log", 0)]
    context = LaunchContext(session=Session(packages=_EMPTY))
    with pytest.raises(SubstitutionFailure, match="handles no events"):
        context.register_event_handler(object())
