"""The README stays a short front page whose links all lead somewhere.

mkdocs' strict build checks the links between the site's pages; the README is read on the
forge, outside the site, so its links and their ``#anchors`` are checked here.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from markdown.extensions.toc import slugify

from tests.docs.runner import ROOT

README = ROOT / "README.md"
_LINK = re.compile(r"\]\(([^)\s]+)\)")


def _links() -> list[str]:
    return [target for target in _LINK.findall(README.read_text()) if "://" not in target]


def _anchors(page: Path) -> set[str]:
    """The ``#anchors`` of a page's headings, as mkdocs' toc extension makes them."""
    text = re.sub(r"^```.*?^```", "", page.read_text(), flags=re.M | re.S)
    headings = re.findall(r"^#{1,6}\s+(.+?)\s*$", text, flags=re.M)
    return {slugify(re.sub(r"[`*]", "", heading), "-") for heading in headings}


def test_readme_is_short_with_a_viewer_screenshot() -> None:
    text = README.read_text()
    assert len(text.splitlines()) <= 150
    images = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert images and all((ROOT / image).is_file() for image in images), images


@pytest.mark.parametrize("target", _links())
def test_readme_link_leads_to_a_file_and_heading(target: str) -> None:
    path, _, anchor = target.partition("#")
    page = ROOT / path
    assert page.exists(), f"README links to {path}, which does not exist"
    if anchor:
        assert anchor in _anchors(page), f"{path} has no heading for #{anchor}"
