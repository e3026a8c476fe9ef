"""The one place the viewer makes markdown: text from a file or a peer is never markup.

viser renders a markdown element with raw HTML enabled (its client's ``rehypeRawDom`` parses
any HTML in it with the browser's parser, unsanitised), so a config value such as
``<iframe srcdoc="<script>...">`` quoted in an error message would run script in the page's
origin. Every markdown element of the viewer is made by :func:`safe_markdown`, whose handle
takes only :class:`Markup`:

- :func:`md` fills a template written in the code (``md("**Not saved**: {}", exc)``) with
  values escaped by :func:`escape_markdown`;
- :func:`code` shows a value as an inline code span;
- a plain ``str`` given to the handle is escaped as a whole, so a forgotten :func:`md` shows
  backslashes, never markup.

A test scans the viewer's source and fails on any ``add_markdown`` or ``add_html`` call, or
any ``.content`` assignment, outside this module.
"""

from __future__ import annotations

import re
from typing import Any

from robomodel._escape import escape_name

__all__ = ["Markup", "SafeMarkdown", "code", "escape_markdown", "md", "safe_markdown"]

# CommonMark lets a backslash escape any ASCII punctuation character (spec 2.4). These start
# an HTML tag or entity, a link or image, emphasis, a code span, a heading, a table cell or a
# strikethrough (GFM) anywhere in a line; quotes, slashes, dots and parentheses mean nothing
# there and are left as they are, so a path or a quoted name reads as written.
_INLINE = re.compile(r"([\\`*_\[\]<>#|~&])")
# At the start of a line: a list item (``-``, ``+``, ``1.``, ``1)``), a setext underline
# (``=``) or a block quote (``>``, escaped above).
_LINE_START = re.compile(r"^(\s*)([-+=]|\d+(?=[.)]))")


class Markup(str):
    """Markdown text that is safe to render: written in the code, or escaped."""

    __slots__ = ()


def _line(line: str) -> str:
    line = _INLINE.sub(r"\\\1", line)
    start = _LINE_START.match(line)
    if start is None:
        return line
    indent, marker = start.groups()
    rest = line[start.end() :]
    if marker[0].isdigit():  # 1. -> 1\.
        return f"{indent}{marker}\\{rest}"
    return f"{indent}\\{marker}{rest}"


def escape_markdown(text: object) -> Markup:
    """``text`` shown literally: markdown's punctuation backslash-escaped, control characters
    written as ``\\x1b`` (:func:`robomodel._escape.escape_name`), line breaks kept as breaks
    inside one paragraph."""
    lines = str(text).splitlines() or [""]
    escaped = (_line(escape_name(line)) for line in lines)
    return Markup("  \n".join(escaped))  # two spaces: a hard break, never a new block


def code(text: object) -> Markup:
    """``text`` as one inline code span. A code span shows its content as text, raw HTML
    included; backticks (which would end it) become ``'`` and line breaks (a blank line would
    end the paragraph) become spaces."""
    value = escape_name(" ".join(str(text).splitlines())).replace("`", "'")
    return Markup(f"`{value}`" if value.strip() else "` `")


def md(template: str, *values: object) -> Markup:
    """``template`` (markdown written in the code) with each ``{}`` filled by the next of
    ``values``: a :class:`Markup` as it is, anything else through :func:`escape_markdown`."""
    return Markup(
        template.format(*(v if isinstance(v, Markup) else escape_markdown(v) for v in values))
    )


def as_markup(text: str) -> Markup:
    """``text`` if it is already :class:`Markup`, else ``text`` escaped."""
    return text if isinstance(text, Markup) else escape_markdown(text)


class SafeMarkdown:
    """A viser markdown element whose content is always :class:`Markup`.

    Args:
        handle: viser's ``GuiMarkdownHandle``.
    """

    __slots__ = ("_handle",)

    def __init__(self, handle: Any) -> None:
        self._handle = handle

    @property
    def content(self) -> Markup:
        """What the element shows (set: a plain ``str`` is escaped)."""
        return Markup(self._handle.content)

    @content.setter
    def content(self, text: str) -> None:
        self._handle.content = as_markup(text)

    @property
    def visible(self) -> bool:
        return bool(self._handle.visible)

    @visible.setter
    def visible(self, value: bool) -> None:
        self._handle.visible = value

    def remove(self) -> None:
        self._handle.remove()


def safe_markdown(gui: Any, content: str = "", **kwargs: Any) -> SafeMarkdown:
    """``gui.add_markdown`` with ``content`` as :class:`Markup` (a plain ``str`` is escaped)."""
    return SafeMarkdown(gui.add_markdown(as_markup(content), **kwargs))
