"""Put the screenshots the documentation shows into docs/assets/, taking the missing ones.

The pictures in docs/ are the browser tests' own (``save_shot(page, "NAME")`` in tests/viewer/
keeps them in build/viewer-screenshots/), never drawn by hand, and committed under docs/assets/
(tests/docs/test_images.py fails when a page names a missing image). For each ``assets/NAME.png``
a page names that docs/assets/ lacks, this runs the test that saves it and copies
build/viewer-screenshots/NAME.png. ``--retake`` takes them all anew. The tests run with
``ROBOMODEL_TEST_ANTIALIAS=1``: the browser draws with multisampling, as a reader's does, where
the test suite's browser saves its CPU by drawing without it (tests/viewer/conftest.py), so a
picture a ``make test`` left in build/viewer-screenshots/ is not reused.
"""

from __future__ import annotations

import ast
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHOTS = ROOT / "build" / "viewer-screenshots"
ASSETS = ROOT / "docs" / "assets"


def wanted() -> set[str]:
    """The screenshot names the documentation's pages show."""
    names: set[str] = set()
    for page in (ROOT / "docs").rglob("*.md"):
        names.update(re.findall(r"assets/([\w.\-]+)\.png", page.read_text()))
    return names


def takers() -> dict[str, str]:
    """Screenshot name -> the pytest node id of the test that saves it."""
    found: dict[str, str] = {}
    for module in sorted((ROOT / "tests" / "viewer").glob("test_*.py")):
        tree = ast.parse(module.read_text())
        for function in tree.body:
            if not isinstance(function, ast.FunctionDef) or not function.name.startswith("test_"):
                continue
            for node in ast.walk(function):
                if (
                    isinstance(node, ast.Call)
                    and getattr(node.func, "id", "") == "save_shot"
                    and len(node.args) == 2
                    and isinstance(node.args[1], ast.Constant)
                ):
                    node_id = f"{module.relative_to(ROOT)}::{function.name}"
                    found.setdefault(str(node.args[1].value), node_id)
    return found


def main() -> int:
    retake = "--retake" in sys.argv[1:]
    needed = sorted(name for name in wanted() if retake or not (ASSETS / f"{name}.png").exists())
    if not needed:
        return 0
    known = takers()
    unknown = [name for name in needed if name not in known]
    if unknown:
        print(f"docs: no browser test saves {', '.join(unknown)} (save_shot)", file=sys.stderr)
        return 2
    tests = sorted({known[name] for name in needed})
    print(f"docs: taking {len(needed)} screenshots with {len(tests)} browser tests", flush=True)
    code = subprocess.call(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *tests],
        env={**os.environ, "ROBOMODEL_TEST_ANTIALIAS": "1"},
    )
    if code != 0:
        return code
    for name in needed:
        shutil.copyfile(SHOTS / f"{name}.png", ASSETS / f"{name}.png")
        print(f"docs: docs/assets/{name}.png (commit it)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
