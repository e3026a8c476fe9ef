"""``robomodel graph``: urdf_to_graphviz's graph, as .gv text or rendered by Graphviz."""

from __future__ import annotations

import argparse
import contextlib
import os
import shutil
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from robomodel._atomic import atomic_write_bytes, atomic_write_text
from robomodel.cli._common import add_description_arguments, load_from_args
from robomodel.cli._verbs import verb_help
from robomodel.description.report import graphviz_text
from robomodel.errors import RobomodelError

__all__ = ["register", "render_dot"]

_RENDERED = {".svg": "svg", ".pdf": "pdf", ".png": "png"}


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "graph",
        help=verb_help("graph"),
        description=(
            "Write the link/joint graph that urdf_to_graphviz writes. Without -o, as "
            "urdf_to_graphviz does: ROBOT.gv and ROBOT.pdf (the robot's name) in the current "
            "folder. -o FILE.gv|.dot writes the text, -o FILE.svg|.pdf|.png renders it with "
            "Graphviz's dot, -o - prints the .gv text."
        ),
    )
    add_description_arguments(parser)
    parser.add_argument(
        "-o",
        "--output",
        metavar="OUT",
        help="output file (.gv, .dot, .svg, .pdf, .png), or - for the .gv text on stdout "
        "(default: ROBOT.gv and ROBOT.pdf in the current folder)",
    )
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
    with _terminate_as_exit():
        proc = subprocess.run(
            [dot, f"-T{fmt}"],
            input=dot_text.encode(),
            capture_output=True,
            preexec_fn=_die_with_parent,
        )
        if proc.returncode != 0:
            raise RobomodelError(f"dot failed: {proc.stderr.decode(errors='replace').strip()}")
        # dot's output comes through a pipe: the only file ever created beside the target is
        # atomic_write_bytes' temporary, which lives for one write and is removed on any error.
        atomic_write_bytes(target, proc.stdout)


def _die_with_parent() -> None:  # pragma: no cover - runs in the child between fork and exec
    """Have the kernel send dot SIGKILL when robomodel dies (Linux PR_SET_PDEATHSIG), so a
    killed ``robomodel graph`` never leaves dot running (it used to finish and write a file)."""
    if sys.platform.startswith("linux"):
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG = 1


@contextlib.contextmanager
def _terminate_as_exit() -> Iterator[None]:
    """Turn SIGTERM into SystemExit while rendering, so the cleanup of a half-written
    temporary file runs (Python's default SIGTERM action exits without any)."""

    def exit_on_term(signum: int, frame: object) -> None:
        raise SystemExit(128 + signum)

    try:
        previous = signal.signal(signal.SIGTERM, exit_on_term)
    except ValueError:  # not the main thread: leave signals alone
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def run(args: argparse.Namespace) -> int:
    result, _, _ = load_from_args(args)
    text = graphviz_text(result.robot)
    if args.output == "-":
        sys.stdout.write(text)
        return 0
    if args.output is None:
        # urdf_to_graphviz FILE: $ROBOT_NAME.gv, then dot -Tpdf to $ROBOT_NAME.pdf, in the CWD
        gv, pdf = f"{result.robot.name}.gv", f"{result.robot.name}.pdf"
        atomic_write_text(gv, text)
        print(f"Created file {gv}")
        render_dot(text, pdf)
        print(f"Created file {pdf}")
        return 0
    if args.output.endswith(".gv") or args.output.endswith(".dot"):
        atomic_write_text(args.output, text)
    else:
        render_dot(text, args.output)
    print(f"Created file {args.output}")
    return 0
