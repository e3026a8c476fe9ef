"""``robomodel graph``: urdf_to_graphviz's graph, as .gv text or rendered by Graphviz."""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

from robomodel._atomic import atomic_write_text, default_file_mode
from robomodel.cli._common import add_description_arguments, load_from_args
from robomodel.description.report import graphviz_text
from robomodel.errors import RobomodelError

__all__ = ["register", "render_dot"]

_RENDERED = {".svg": "svg", ".pdf": "pdf", ".png": "png"}


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "graph",
        help="draw the link/joint tree (urdf_to_graphviz)",
        description=(
            "Write the link/joint graph that urdf_to_graphviz writes. Without -o the .gv text "
            "goes to stdout; -o FILE.svg|.pdf|.png renders it with Graphviz's dot."
        ),
    )
    add_description_arguments(parser)
    parser.add_argument("-o", "--output", metavar="OUT", help="output file (.gv, .svg, .pdf, .png)")
    parser.set_defaults(func=run)


def render_dot(dot_text: str, output: str | os.PathLike[str]) -> None:
    """Render Graphviz text to ``output`` (format from its suffix), atomically."""
    target = Path(output)
    fmt = _RENDERED.get(target.suffix.lower())
    if fmt is None:
        raise RobomodelError(
            f"unsupported output '{target}'; use a .gv, .svg, .pdf or .png file name"
        )
    dot = shutil.which("dot")
    if dot is None:
        raise RobomodelError(
            "rendering needs Graphviz's 'dot', which is not installed: apt-get install graphviz "
            "(Debian/Ubuntu), brew install graphviz (macOS); or write .gv text with -o FILE.gv"
        )
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=target.suffix, dir=target.parent)
    os.close(fd)
    try:
        proc = subprocess.run(
            [dot, f"-T{fmt}", "-o", tmp], input=dot_text, text=True, capture_output=True
        )
        if proc.returncode != 0:
            raise RobomodelError(f"dot failed: {proc.stderr.strip()}")
        os.chmod(tmp, default_file_mode())
        os.replace(tmp, target)
    finally:
        Path(tmp).unlink(missing_ok=True)


def run(args: argparse.Namespace) -> int:
    result, _, _ = load_from_args(args)
    text = graphviz_text(result.robot)
    if args.output is None:
        sys.stdout.write(text)
        return 0
    if args.output.endswith(".gv") or args.output.endswith(".dot"):
        atomic_write_text(args.output, text)
    else:
        render_dot(text, args.output)
    print(f"Created file {args.output}")
    return 0
