"""argparse classes whose help formatter does not import :mod:`shutil`.

argparse builds a ``HelpFormatter`` for every ``add_argument`` (to check the metavar), and the
stock one imports ``shutil`` (with ``bz2`` and ``lzma``) to ask for the terminal width: about
2 ms of every command's start-up. This formatter finds the width the way
``shutil.get_terminal_size`` does, with :mod:`os` alone, so the help text is the same.
"""

from __future__ import annotations

import argparse
import os
import sys

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (start-up)
if TYPE_CHECKING:
    from typing import Any

__all__ = ["Formatter", "Parser", "terminal_columns"]


def terminal_columns(fallback: int = 80) -> int:
    """``shutil.get_terminal_size().columns``: $COLUMNS, else stdout's terminal, else 80."""
    try:
        columns = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns  # type: ignore[union-attr]
        except (AttributeError, ValueError, OSError):
            columns = fallback
        columns = columns or fallback
    return columns


class Formatter(argparse.HelpFormatter):
    """``argparse.HelpFormatter`` with the terminal width found without ``shutil``."""

    def __init__(
        self,
        prog: str,
        indent_increment: int = 2,
        max_help_position: int = 24,
        width: int | None = None,
    ) -> None:
        if width is None:
            width = terminal_columns() - 2
        super().__init__(prog, indent_increment, max_help_position, width)


class Parser(argparse.ArgumentParser):
    """``argparse.ArgumentParser`` using :class:`Formatter` unless told otherwise.

    Sub-parsers are made of the parent's class, so every verb's parser uses it too.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("formatter_class", Formatter)
        super().__init__(*args, **kwargs)
