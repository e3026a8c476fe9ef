"""mkdocs hooks: output blocks styled apart from commands, the screenshots from the tests.

- ``build/viewer-screenshots/*.png`` (saved by the browser tests) become ``screenshots/*.png``
  in the site; tools/docs_screenshots.py takes the missing ones before the build.
- A block marked ``<!-- output ... -->`` (what a command printed, compared by tests/docs) gets
  the class ``output``, so that the reader tells it from a command (docs/stylesheets/extra.css).
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from mkdocs.structure.files import File, Files

ROOT = Path(__file__).resolve().parents[1]
SHOTS = ROOT / "build" / "viewer-screenshots"


_OUTPUT = re.compile(r'<!-- output[^>]*-->\s*<div class="highlight">')


def on_page_content(html: str, page: Any, config: Any, files: Files) -> str:
    return _OUTPUT.sub('<div class="highlight output">', html)


def on_files(files: Files, config: Any) -> Files:
    for shot in sorted(SHOTS.glob("*.png")):
        files.append(
            File.generated(config, f"screenshots/{shot.name}", abs_src_path=str(shot))
        )
    return files
