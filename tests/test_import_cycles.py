"""Import circles: every one that exists is named in docs/explanation/architecture.md.

``tools/import_cycles.py`` lists the strongly connected components of src/robomodel's import
graph (module- and function-level imports; those only under ``if TYPE_CHECKING`` apart). The
architecture page's "Import circles" section names each one that remains, so a new circle
fails here until it is removed or explained there.
"""

from __future__ import annotations

import functools
import importlib.util
import re
import subprocess
import sys
import textwrap
from pathlib import Path
from types import ModuleType

import pytest

ROOT = Path(__file__).resolve().parent.parent
ARCHITECTURE = ROOT / "docs" / "explanation" / "architecture.md"


def _tool() -> ModuleType:
    spec = importlib.util.spec_from_file_location(
        "import_cycles", ROOT / "tools" / "import_cycles.py"
    )
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up while being made
    spec.loader.exec_module(module)
    return module


def _documented() -> tuple[set[frozenset[str]], set[frozenset[str]]]:
    """The circles the architecture page names: (those that run, those only TYPE_CHECKING makes),
    each bullet of its "Import circles" section read as the set of modules it names in
    backticks; bullets under "Type-only circles" are the second kind."""
    text = ARCHITECTURE.read_text(encoding="utf-8")
    section = text.split("\n## Import circles\n", 1)[1].split("\n## ", 1)[0]
    running, type_only = section.split("\n### Type-only circles\n", 1)
    return _bullets(running), _bullets(type_only)


def _bullets(text: str) -> set[frozenset[str]]:
    circles = set()
    for bullet in re.split(r"\n(?=- )", text):
        if bullet.startswith("- "):
            circles.add(frozenset(re.findall(r"`(robomodel(?:\.\w+)+)`", bullet.split(":")[0])))
    return circles


@functools.cache
def _circles() -> tuple[tuple[frozenset[str], bool], ...]:
    """The circles of src/robomodel (found once: the tests below read them)."""
    return tuple(
        (frozenset(c.modules), c.type_checking_only) for c in _tool().find_circles(ROOT / "src")
    )


# the tests that read the circles of src run on one worker, which finds them once
@pytest.mark.xdist_group("import_circles")
@pytest.mark.parametrize("type_only", [False, True], ids=["running", "type-only"])
def test_every_circle_is_documented_and_every_documented_one_exists(type_only: bool) -> None:
    found = {modules for modules, marked in _circles() if marked is type_only}
    documented = _documented()[type_only]
    missing = sorted(" ↔ ".join(sorted(c)) for c in found - documented)
    assert not missing, (
        "import circles not named in docs/explanation/architecture.md (remove them, or name "
        "each with its reason under 'Import circles'):\n" + "\n".join(missing)
    )
    gone = sorted(" ↔ ".join(sorted(c)) for c in documented - found)
    assert not gone, "architecture.md names import circles that no longer exist:\n" + "\n".join(
        gone
    )


@pytest.mark.xdist_group("import_circles")
def test_the_ros2_shim_the_ros1_loader_and_xacro_are_in_no_circle() -> None:
    """The launch and xacro packages import in layers: no module of theirs is in a circle,
    function-level and ``TYPE_CHECKING`` imports counted."""
    ours = (
        "robomodel.launch.ros2",
        "robomodel.launch.ros1",
        "robomodel.xacro",
        "robomodel.launch.gui",
    )
    assert [
        module for modules, _ in _circles() for module in modules if module.startswith(ours)
    ] == []


def test_the_tool_finds_circles_through_functions_and_marks_type_checking(tmp_path: Path) -> None:
    pkg = tmp_path / "robomodel"
    (pkg / "sub").mkdir(parents=True)
    files = {
        "__init__.py": "",
        "a.py": "from robomodel.b import x\n",
        "b.py": "def f():\n    from robomodel import a\nx = 1\n",
        "c.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from robomodel.d import y\n",
        "d.py": "from robomodel import c\ny = 1\n",
        "e.py": "from .sub import g\n",
        "sub/__init__.py": "",
        "sub/g.py": "from ..e import z\n",
        "lone.py": "import robomodel.a\n",
    }
    for name, text in files.items():
        (pkg / name).write_text(text)
    circles = _tool().find_circles(tmp_path)
    assert [(c.modules, c.type_checking_only) for c in circles] == [
        (("robomodel.a", "robomodel.b"), False),  # the function-level import closes it
        (("robomodel.e", "robomodel.sub.g"), False),  # relative imports resolved
        (("robomodel.c", "robomodel.d"), True),
    ]


def test_the_script_prints_one_circle_a_line(tmp_path: Path) -> None:
    pkg = tmp_path / "robomodel"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("import robomodel.b\n")
    (pkg / "b.py").write_text(
        textwrap.dedent(
            """\
            from typing import TYPE_CHECKING
            if TYPE_CHECKING:
                import robomodel.a
            """
        )
    )
    script = ROOT / "tools" / "import_cycles.py"
    out = subprocess.run(
        [sys.executable, str(script), str(tmp_path)], capture_output=True, text=True, check=True
    )
    assert out.stdout == "robomodel.a ↔ robomodel.b  [TYPE_CHECKING only]\n"
    bad = subprocess.run([sys.executable, str(script), str(pkg)], capture_output=True, text=True)
    assert bad.returncode == 2 and "no robomodel/ package in" in bad.stderr
