"""mkdocs hook: output blocks styled apart from commands.

A block marked ``<!-- output ... -->`` (what a command printed, compared by tests/docs) gets the
class ``output``, so that the reader tells it from a command (docs/stylesheets/extra.css).
"""

from __future__ import annotations

import re
from typing import Any

from mkdocs.structure.files import Files

_OUTPUT = re.compile(r'<!-- output[^>]*-->\s*<div class="highlight">')


def on_page_content(html: str, page: Any, config: Any, files: Files) -> str:
    return _OUTPUT.sub('<div class="highlight output">', html)
