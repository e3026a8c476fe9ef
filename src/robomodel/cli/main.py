"""Entry point of the ``robomodel`` command.

Each verb lives in its own module exposing ``register(subparsers)``, which adds a sub-parser
whose ``func`` default takes the parsed arguments and returns the exit code. Errors derived from
:class:`~robomodel.errors.RobomodelError` become one clear message on stderr and exit code 2;
``--debug`` shows the traceback instead.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Callable, Sequence

from robomodel._version import __version__
from robomodel.errors import InputError, RobomodelError

__all__ = ["EXIT_INVALID", "build_parser", "main"]

EXIT_INVALID = 2

# Verb modules, imported lazily so that `robomodel check` never pays for the viewer or physics.
_VERBS: tuple[str, ...] = (
    "robomodel.cli.check",
    "robomodel.cli.graph",
    "robomodel.cli.new",
    "robomodel.cli.xacro",
    "robomodel.cli.tf",
    "robomodel.cli.frames",
    "robomodel.cli.fk",
    "robomodel.cli.ik",
    "robomodel.cli.topic",
    "robomodel.cli.param",
    "robomodel.cli.service",
    "robomodel.cli.publish_state",
    "robomodel.cli.control",
    "robomodel.cli.view",
    "robomodel.cli.sim",
    "robomodel.cli.launch",
)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="robomodel",
        description="URDF and xacro tools without ROS: check, graph, xacro, new, ...",
    )
    parser.add_argument("--version", action="version", version=f"robomodel {__version__}")
    parser.add_argument("--debug", action="store_true", help="show Python tracebacks for errors")
    subparsers = parser.add_subparsers(dest="verb", metavar="COMMAND")
    subparsers.required = True
    for module_name in _VERBS:
        try:
            module = importlib.import_module(module_name)
        except ModuleNotFoundError as exc:
            if exc.name == module_name:
                continue  # verb not built yet
            raise
        module.register(subparsers)
    return parser


def _report(exc: RobomodelError) -> None:
    if isinstance(exc, InputError):
        print(exc.diagnostic.format(), file=sys.stderr)
        for note in exc.notes:
            print(note.format(), file=sys.stderr)
    else:
        print(f"robomodel: error: {exc}", file=sys.stderr)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line and return its exit code."""
    args_list = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser()
    args = parser.parse_args(args_list)
    func: Callable[[argparse.Namespace], int] = args.func
    try:
        return func(args)
    except RobomodelError as exc:
        if args.debug:
            raise
        _report(exc)
        return EXIT_INVALID
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        return 0


if __name__ == "__main__":
    sys.exit(main())
