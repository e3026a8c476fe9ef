"""mkdocs hooks: the CLI reference from the argument parsers, the screenshots from the tests.

- A page holding ``<!-- cli-reference -->`` gets every verb's and sub-verb's ``--help``, built
  from robomodel's own parsers, so the reference cannot drift from the command.
- ``build/viewer-screenshots/*.png`` (saved by the browser tests) become ``screenshots/*.png``
  in the site; tools/docs_screenshots.py takes the missing ones before the build.
- A block marked ``<!-- output ... -->`` (what a command printed, compared by tests/docs) gets
  the class ``output``, so that the reader tells it from a command (docs/stylesheets/extra.css).
"""

from __future__ import annotations

import argparse
import os
import re
from pathlib import Path
from typing import Any

from mkdocs.structure.files import File, Files

ROOT = Path(__file__).resolve().parents[1]
SHOTS = ROOT / "build" / "viewer-screenshots"
MARKER = "<!-- cli-reference -->"


def _subparsers(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action.choices)
    return {}


def _sections(parser: argparse.ArgumentParser, title: str, depth: int) -> list[str]:
    out = [f"{'#' * depth} `{title}`", "", "```text", parser.format_help().rstrip(), "```", ""]
    for name, sub in _subparsers(parser).items():
        out += _sections(sub, f"{title} {name}", min(depth + 1, 6))
    return out


def cli_reference() -> str:
    """Every verb's help, as ``robomodel VERB [SUB] --help`` prints it at 100 columns."""
    os.environ["COLUMNS"] = "100"
    from robomodel.cli._verbs import VERBS
    from robomodel.cli.main import build_parser

    lines = ["```text", build_parser().format_help().rstrip(), "```", ""]
    for verb in VERBS:
        lines += _sections(_subparsers(build_parser(verb.name))[verb.name], f"robomodel {verb.name}", 2)
    return "\n".join(lines)


def on_page_markdown(markdown: str, page: Any, config: Any, files: Files) -> str:
    if MARKER in markdown:
        return markdown.replace(MARKER, cli_reference())
    return markdown


_OUTPUT = re.compile(r'<!-- output[^>]*-->\s*<div class="highlight">')


def on_page_content(html: str, page: Any, config: Any, files: Files) -> str:
    return _OUTPUT.sub('<div class="highlight output">', html)


def on_files(files: Files, config: Any) -> Files:
    for shot in sorted(SHOTS.glob("*.png")):
        files.append(
            File.generated(config, f"screenshots/{shot.name}", abs_src_path=str(shot))
        )
    return files
