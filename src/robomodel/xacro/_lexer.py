"""Split attribute and text values into literal text, ``${...}`` and ``$(...)`` tokens.

Mirrors the reference ``QuickLexer`` (xacro/__init__.py L693): ``$$+{``/``$$+(`` drop one
dollar, a lone ``$`` is literal, and ``$$x`` is an error. One deliberate fix: ``${...}`` and
``$(...)`` end at the *matching* brace or parenthesis (quote-aware inside ``${}``), so
``${ {'a': 1}['a'] }``, ``${a/2 + ${b}}`` and ``$(eval max(1, 2))`` work. The reference stops at
the first ``}``/``)``, which only ever turned such inputs into errors.
"""

from __future__ import annotations

import re
from enum import IntEnum

__all__ = ["LexError", "TokenKind", "tokenize_text"]


class TokenKind(IntEnum):
    """The kinds of token in a value."""

    TEXT = 0
    EXPR = 1
    EXTENSION = 2


class LexError(ValueError):
    """The text has a ``$`` construct the reference lexer rejects."""


_DOLLARS = re.compile(r"\$\$+[{(]")
_TEXT = re.compile(r"[^$]+|\$[^{($]+|\$$")

Token = tuple[TokenKind, str]


def _match_brace(text: str, start: int) -> int:
    """Return the index of the ``}`` closing the ``{`` at ``start - 1``, or -1."""
    depth = 1
    i = start
    n = len(text)
    while i < n:
        c = text[i]
        if c in "'\"":
            end = text.find(c, i + 1)
            if end < 0:
                return -1
            i = end
        elif c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0:
                return i
        i += 1
    return -1


def _match_paren(text: str, start: int) -> int:
    """Return the index of the ``)`` closing the ``(`` at ``start - 1``, or -1."""
    depth = 1
    for i in range(start, len(text)):
        c = text[i]
        if c == "(":
            depth += 1
        elif c == ")":
            depth -= 1
            if depth == 0:
                return i
    return -1


def _closing(text: str, pos: int, brace: bool) -> int:
    end = _match_brace(text, pos + 2) if brace else _match_paren(text, pos + 2)
    if end < 0:  # unbalanced: fall back to the reference's "first closing character"
        end = text.find("}" if brace else ")", pos + 2)
    return end


def tokenize_text(text: str) -> tuple[Token, ...]:
    """Split ``text`` into tokens; expression tokens carry their inner text.

    Raises:
        LexError: a ``$`` sequence the reference lexer cannot tokenize either.
    """
    tokens: list[Token] = []
    pos = 0
    n = len(text)
    while pos < n:
        if text[pos] == "$" and pos + 1 < n:
            nxt = text[pos + 1]
            if nxt == "$":
                m = _DOLLARS.match(text, pos)
                if m:
                    tokens.append((TokenKind.TEXT, m.group(0)[1:]))
                    pos = m.end()
                    continue
            elif nxt in "{(":
                end = _closing(text, pos, nxt == "{")
                if end >= 0:
                    kind = TokenKind.EXPR if nxt == "{" else TokenKind.EXTENSION
                    tokens.append((kind, text[pos + 2 : end]))
                    pos = end + 1
                    continue
        m = _TEXT.match(text, pos)
        if not m:
            raise LexError(f"invalid expression: {text[pos:]}")
        tokens.append((TokenKind.TEXT, m.group(0)))
        pos = m.end()
    return tuple(tokens)
