"""The launch and xacro packages import in layers: no module of theirs is in an import circle,
function-level and ``TYPE_CHECKING`` imports counted (tools/import_cycles.py)."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[2]


def _tool() -> ModuleType:
    spec = importlib.util.spec_from_file_location("import_cycles", ROOT / "tools/import_cycles.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["import_cycles"] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def test_the_ros2_shim_the_ros1_loader_and_xacro_are_in_no_circle() -> None:
    ours = (
        "robomodel.launch.ros2",
        "robomodel.launch.ros1",
        "robomodel.xacro",
        "robomodel.launch.gui",
    )
    caught = [
        module
        for circle in _tool().find_circles(ROOT / "src")
        for module in circle.modules
        if module.startswith(ours)
    ]
    assert caught == []
