"""``robomodel xacro``: expand a xacro file like the ``xacro`` command of ROS 2 (xacro 2.1.1).

Same arguments, output bytes and exit codes as the reference CLI (``xacro/cli.py``), plus
``--package-path``/``--package`` to resolve ``$(find pkg)`` without ROS. ``-o`` writes
atomically: on error no file (not even an empty one) is left behind.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from robomodel._atomic import atomic_write_text
from robomodel.cli._verbs import verb_help
from robomodel.description.packages import index_from_options
from robomodel.errors import Diagnostic, RobomodelError, Severity

__all__ = ["load_mappings", "register", "run"]

_REMAP = ":="


def load_mappings(argv: Sequence[str]) -> dict[str, str]:
    """``name:=value`` arguments as a dict; private ``_name`` mappings are dropped (as ROS)."""
    mappings: dict[str, str] = {}
    for arg in argv:
        if _REMAP not in arg:
            continue
        parts = [x.strip() for x in arg.split(_REMAP)]
        if len(parts) != 2:
            raise RobomodelError(f"invalid remapping argument '{arg}' (expected name:=value)")
        src, dst = parts
        if src and dst and not (len(src) > 1 and src[0] == "_" and src[1] != "_"):
            mappings[src] = dst
    return mappings


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Add the ``xacro`` verb."""
    parser = subparsers.add_parser(
        "xacro",
        help=verb_help("xacro"),
        description="Expand a xacro file to URDF; output is byte-identical to ROS xacro 2.1.1.",
    )
    parser.add_argument("input", help="the .xacro file")
    parser.add_argument("mappings", nargs="*", metavar="name:=value", help="xacro:arg values")
    parser.add_argument("-o", dest="output", metavar="FILE", help="write to FILE, not stdout")
    parser.add_argument("--deps", action="store_true", help="print the file dependencies")
    parser.add_argument(
        "-i", "--inorder", action="store_true", help="accepted and ignored (always in order)"
    )
    parser.add_argument("--root-dir", metavar="DIR", help="base for relative paths and $(cwd)")
    parser.add_argument("-q", dest="verbosity", action="store_const", const=0, help="quiet")
    parser.add_argument("-v", dest="verbosity", action="count", help="more verbose")
    parser.add_argument("--verbosity", dest="verbosity", type=int, metavar="LEVEL")
    parser.add_argument(
        "--package-path", action="append", default=[], metavar="DIR",
        help="directory scanned for package.xml, for $(find pkg) (repeatable)",
    )  # fmt: skip
    parser.add_argument(
        "--package", action="append", default=[], metavar="NAME=DIR",
        help="explicit package location for $(find NAME) (repeatable)",
    )  # fmt: skip
    parser.set_defaults(func=run, verbosity=1)


def _print_diagnostics(diagnostics: Sequence[Diagnostic], verbosity: int) -> None:
    if verbosity <= 0:
        return
    for diagnostic in diagnostics:
        if diagnostic.severity is Severity.NOTE and diagnostic.location.line is None:
            print(diagnostic.message, file=sys.stderr)
        else:
            print(diagnostic.format(), file=sys.stderr)


def run(args: argparse.Namespace) -> int:
    """Expand ``args.input``; errors propagate as :class:`RobomodelError` (exit code 2)."""
    from robomodel.xacro import expand

    positional = [args.input, *args.mappings]  # name:=value may come before the file too
    inputs = [p for p in positional if _REMAP not in p]
    if len(inputs) != 1:
        found = " ".join(inputs) or "none"
        raise RobomodelError(
            f"expected exactly one input file, got: {found} (other arguments are name:=value)"
        )
    if args.inorder:
        print(
            "xacro: in-order processing became default in ROS Melodic. You can drop the option.",
            file=sys.stderr,
        )
    # The input's own package and its workspace siblings resolve without any setup.
    index = index_from_options(args.package_path, args.package).with_workspace_of(inputs[0])
    result = expand(
        inputs[0],
        mappings=load_mappings(positional),
        package_index=index,
        root_dir=args.root_dir,
    )
    _print_diagnostics(result.warnings, args.verbosity or 0)
    text = " ".join(result.includes) if args.deps else result.text
    if args.output:
        try:
            atomic_write_text(args.output, text)
        except OSError as exc:
            raise RobomodelError(f"cannot write '{args.output}': {exc.strerror or exc}") from None
    else:
        sys.stdout.write(text)
        sys.stdout.flush()
    return 0
