"""The launch and xacro packages import in layers: no module of theirs is in an import circle,
function-level imports counted (tools/import_cycles.py)."""

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


def _circles(root: Path, package: str, *, runtime_only: bool = False) -> list[list[str]]:
    tool = _tool()
    modules = tool.module_names(root, package)
    edges = [e for e in tool.edges(modules) if not (runtime_only and e.kind == "typing")]
    found: list[list[str]] = tool.components(sorted(modules), edges)
    return found


def test_the_ros2_shim_the_ros1_loader_and_xacro_are_in_no_circle() -> None:
    circles = _circles(ROOT / "src", "robomodel")
    ours = (
        "robomodel.launch.ros2",
        "robomodel.launch.ros1",
        "robomodel.xacro",
        "robomodel.launch.gui",
    )
    caught = [m for circle in circles for m in circle if m.startswith(ours)]
    assert caught == []


def _package(tmp_path: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = tmp_path / "pkg" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return tmp_path


def test_the_tool_finds_a_circle_held_by_a_function_level_import(tmp_path: Path) -> None:
    root = _package(
        tmp_path,
        {
            "__init__.py": "",
            "a.py": "from pkg.b import f\n",
            "b.py": "def f():\n    from pkg import a\n    return a\n",
            "c.py": "import pkg.a\n",
        },
    )
    assert _circles(root, "pkg") == [["pkg.a", "pkg.b"]]


def test_type_checking_imports_are_marked_and_can_be_left_out(tmp_path: Path) -> None:
    root = _package(
        tmp_path,
        {
            "__init__.py": "from pkg.a import A\n",
            "a.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from pkg.b import B\nA = 1\n",
            "b.py": "from pkg.a import A\nB = A\n",
        },
    )
    tool = _tool()
    kinds = {(e.source, e.target): e.kind for e in tool.edges(tool.module_names(root, "pkg"))}
    assert kinds[("pkg.a", "pkg.b")] == "typing" and kinds[("pkg.b", "pkg.a")] == "module"
    assert _circles(root, "pkg") == [["pkg.a", "pkg.b"]]
    assert _circles(root, "pkg", runtime_only=True) == []
    # a submodule importing a sibling through its own package is no circle: Python has set the
    # package up before the submodule runs
    assert ("pkg.b", "pkg") not in kinds
