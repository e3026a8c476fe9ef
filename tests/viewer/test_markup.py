"""Nothing from a file or a peer is rendered as markup in the viewer's page.

viser renders markdown with raw HTML enabled, so every markdown element goes through
``robomodel.viewer.markup``; these tests render what it makes with a CommonMark parser that
also passes raw HTML through (markdown-it with ``html=True``), as the page's renderer does.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from markdown_it import MarkdownIt

from robomodel.viewer.markup import Markup, code, escape_markdown, md, safe_markdown
from tests.conftest import ROOT

VIEWER = ROOT / "src/robomodel/viewer"

HOSTILE = (
    '<iframe srcdoc="<script>parent.document.title=1</script>">',
    "<img src=x onerror=alert(1)>",
    "a`<script>alert(1)</script>`b",
    "x\n\n<script>alert(1)</script>",
    "[click](javascript:alert(1))",
    "&lt;script&gt;",
    "\\<b>bold\\</b>",
    "**bold** _em_ # head | cell ~strike~",
    "\x1b]0;title\x07 \u202e",
)


def _html(markdown: str) -> str:
    return MarkdownIt("commonmark", {"html": True}).render(markdown)


@pytest.mark.parametrize("text", HOSTILE)
def test_escaped_text_renders_as_the_text_and_never_as_a_tag(text: str) -> None:
    html = _html(md("**Not opened**: {}", text))
    assert html.startswith("<p><strong>Not opened</strong>: ")  # the template's own markup
    for tag in ("<iframe", "<script", "<img", "<a ", "<em>", "<b>", "<code>", "<h1>"):
        assert tag not in html.split("</strong>", 1)[1], html


@pytest.mark.parametrize("text", HOSTILE)
def test_code_spans_hold_the_whole_value(text: str) -> None:
    html = _html(md("file {} here", code(text)))
    assert html.count("<code>") == 1 and "<script" not in html and "<iframe" not in html, html
    assert html.rstrip().endswith("</code> here</p>")


def test_the_text_is_shown_as_written() -> None:
    html = _html(escape_markdown("a_b*c* [d](e) <f> & 1. #g 'h' /i.j"))
    assert html == "<p>a_b*c* [d](e) &lt;f&gt; &amp; 1. #g 'h' /i.j</p>\n"
    lines = "# not a heading\n- not a list\n2) nor this\n===\n> nor a quote"
    assert _html(escape_markdown(lines)) == (
        "<p># not a heading<br />\n- not a list<br />\n2) nor this<br />\n===<br />\n"
        "&gt; nor a quote</p>\n"
    )


class _Handle:
    def __init__(self, content: str) -> None:
        self.content = content
        self.visible = True


class _Gui:
    def add_markdown(self, content: str, **_kwargs: object) -> _Handle:
        return _Handle(content)


def test_a_plain_string_given_to_the_element_is_escaped_as_a_whole() -> None:
    element = safe_markdown(_Gui(), "<b>x</b>")
    assert "<b>" not in _html(element.content)
    element.content = "**not bold** <i>"
    assert "<strong>" not in _html(element.content) and "<i>" not in _html(element.content)
    element.content = md("**bold** {}", "<i>")
    assert "<strong>bold</strong>" in _html(element.content) and "<i>" not in _html(element.content)
    assert isinstance(element.content, Markup)


def _markup_calls(tree: ast.AST) -> list[tuple[int, str]]:
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and node.attr in ("add_markdown", "add_html"):
            found.append((node.lineno, node.attr))
        elif isinstance(node, ast.Constant) and node.value in ("add_markdown", "add_html"):
            found.append((node.lineno, str(node.value)))  # getattr(gui, "add_html")
    return found


def test_viewer_code_makes_markdown_only_through_safe_markdown() -> None:
    offenders = []
    for path in sorted(VIEWER.rglob("*.py")):
        if path == VIEWER / "markup.py":
            continue
        tree = ast.parse(path.read_text(), str(path))
        offenders += [
            f"{path.relative_to(ROOT)}:{line}: {attr}" for line, attr in _markup_calls(tree)
        ]
    assert not offenders, "use robomodel.viewer.markup.safe_markdown:\n" + "\n".join(offenders)


def test_the_scan_finds_a_direct_call() -> None:
    source = (
        "def f(gui, exc):\n    gui.add_markdown(f'**{exc}**')\n    getattr(gui, 'add_html')('')\n"
    )
    assert _markup_calls(ast.parse(source)) == [(2, "add_markdown"), (3, "add_html")]


def test_open_config_quotes_a_hostile_frame_rate_as_text(tmp_path: Path) -> None:
    """A ``.rviz`` whose Frame Rate is an iframe: Open Config's error quotes it, as text."""
    from robomodel.viewer.config_panel import ConfigPanel
    from robomodel.viewer.rviz_document import open_rviz_document
    from robomodel.viewer.rviz_model import RvizDialect

    bad = tmp_path / "bad.rviz"
    payload = '<iframe srcdoc="<script>parent.document.title=1</script>">'
    bad.write_text(f"Visualization Manager:\n  Global Options:\n    Frame Rate: '{payload}'\n")

    class _Server:
        gui = _PanelGui()
        initial_camera = None

    document, _ = open_rviz_document(None, RvizDialect.ROS2)
    panel = ConfigPanel(_Server(), document, lambda _camera: None, reopen=lambda _doc: None)  # type: ignore[arg-type, return-value]
    assert not panel.open(str(bad))
    html = _html(panel.status.content)
    assert "Not opened" in html and "Frame Rate" in html
    assert "<iframe" not in html and "<script" not in html
    assert "&lt;iframe srcdoc=&quot;&lt;script&gt;" in html  # shown, as written


class _PanelGui(_Gui):
    class _Context:
        def __enter__(self) -> None:
            return None

        def __exit__(self, *_args: object) -> None:
            return None

    class _Button:
        def on_click(self, _callback: object) -> None:
            return None

    def add_folder(self, _label: str) -> _Context:
        return self._Context()

    def add_button(self, _label: str, **_kwargs: object) -> _Button:
        return self._Button()
