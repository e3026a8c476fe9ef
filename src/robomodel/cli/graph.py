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
DOT_TIMEOUT_S = 60.0  # a robot's tree renders in well under a second
MAX_DOT_BYTES = 8 * 1024 * 1024  # Graphviz text handed to dot (a 1,000-frame tree: ~300 KiB)
DOT_MEMORY_BYTES = 2 * 1024**3  # dot's address space


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


def render_dot(
    dot_text: str, output: str | os.PathLike[str], *, timeout_s: float = DOT_TIMEOUT_S
) -> None:
    """Render Graphviz text to ``output`` (format from its suffix), atomically.

    dot runs with a timeout (``timeout_s``), on text of at most ``MAX_DOT_BYTES`` and in at
    most ``DOT_MEMORY_BYTES`` of memory: a graph of names from peers cannot keep it running.
    """
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
    data = dot_text.encode()
    if len(data) > MAX_DOT_BYTES:
        raise RobomodelError(
            f"the graph for '{target}' is {len(data)} bytes of Graphviz text, more than the "
            f"{MAX_DOT_BYTES} dot is given; write the .gv text with -o FILE.gv instead"
        )
    with _terminate_as_exit():
        try:
            proc = subprocess.run(
                [dot, f"-T{fmt}"],
                input=data,
                capture_output=True,
                preexec_fn=_die_with_parent,
                timeout=timeout_s,
            )
        except subprocess.TimeoutExpired:
            raise RobomodelError(
                f"dot did not render '{target}' within {timeout_s:g} s; the .gv text is "
                "written, render it with dot yourself"
            ) from None
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
    with contextlib.suppress(ImportError, ValueError, OSError):
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (DOT_MEMORY_BYTES, DOT_MEMORY_BYTES))


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
