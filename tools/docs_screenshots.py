"""Take the screenshots the documentation shows and that build/viewer-screenshots/ lacks.

The pictures in docs/ are the browser tests' own (``save_shot(page, "NAME")`` in tests/viewer/),
never drawn by hand. After ``make test`` they are all there; otherwise this finds, for each
missing ``screenshots/NAME.png`` named in docs/, the test that saves it and runs those tests.
"""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHOTS = ROOT / "build" / "viewer-screenshots"


def wanted() -> set[str]:
    """The screenshot names the documentation's pages show."""
    names: set[str] = set()
    for page in (ROOT / "docs").rglob("*.md"):
        names.update(re.findall(r"screenshots/([\w.\-]+)\.png", page.read_text()))
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
    missing = sorted(name for name in wanted() if not (SHOTS / f"{name}.png").exists())
    if not missing:
        return 0
    known = takers()
    unknown = [name for name in missing if name not in known]
    if unknown:
        print(f"docs: no browser test saves {', '.join(unknown)} (save_shot)", file=sys.stderr)
        return 2
    tests = sorted({known[name] for name in missing})
    print(f"docs: taking {len(missing)} screenshots with {len(tests)} browser tests", flush=True)
    return subprocess.call([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *tests])


if __name__ == "__main__":
    sys.exit(main())
