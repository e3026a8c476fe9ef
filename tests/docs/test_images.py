"""Every image a page of the documentation (or the README) shows is a committed file."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.docs.runner import ROOT

PAGES = [*sorted((ROOT / "docs").rglob("*.md")), ROOT / "README.md"]
# ![alt](path "title") and <img src="path">
_IMAGE = re.compile(r"!\[[^\]]*\]\(([^)\s]+)[^)]*\)|<img[^>]*\ssrc=\"([^\"]+)\"")


def images(page: Path) -> list[tuple[int, str]]:
    """(line, target) of every local image ``page`` shows."""
    text = page.read_text()
    found = []
    for match in _IMAGE.finditer(text):
        target = match.group(1) or match.group(2)
        if not re.match(r"[a-z]+://", target):
            found.append((text[: match.start()].count("\n") + 1, target))
    return found


def test_pages_show_images() -> None:
    assert sum(len(images(page)) for page in PAGES) >= 10  # the pattern finds them


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_image_a_page_shows_is_committed(page: Path) -> None:
    missing = [
        f"{page.relative_to(ROOT)}:{line}: {target}"
        for line, target in images(page)
        if not (page.parent / target.split("#")[0]).is_file()
    ]
    assert not missing, (
        "images that do not exist (python tools/docs_screenshots.py copies the browser tests' "
        f"screenshots into docs/assets/): {missing}"
    )
