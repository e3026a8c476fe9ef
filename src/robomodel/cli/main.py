"""Entry point of the ``robomodel`` command.

Each verb lives in its own module exposing ``register(subparsers)``, which adds a sub-parser
whose ``func`` default takes the parsed arguments and returns the exit code. Errors derived from
:class:`~robomodel.errors.RobomodelError` become one clear message on stderr and exit code 2;
``--debug`` shows the traceback instead.
"""

from __future__ import annotations

import importlib
import sys

from robomodel._version import __version__
from robomodel.cli._verbs import VERBS

# Start-up matters here (`robomodel --version` should cost little more than starting Python),
# so this module imports argparse, typing and the error classes only where they are used.
TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (mypy knows the name)
if TYPE_CHECKING:
    import argparse
    from collections.abc import Callable, Sequence

    from robomodel.errors import RobomodelError

__all__ = ["EXIT_INVALID", "build_parser", "main"]

EXIT_INVALID = 2
_VERB_NAMES = frozenset(verb.name for verb in VERBS)
_VERSION_TEXT = f"robomodel {__version__}"


def build_parser(verb: str | None = None) -> argparse.ArgumentParser:
    """The ``robomodel`` parser; with ``verb``, only that verb's sub-parser is built in full.

    The other verbs get an empty sub-parser carrying their help line from the static table, so
    ``--help``, the list of choices and the errors are the same as with every verb built, while
    a run imports only the module of the verb it runs (``robomodel check`` never loads the
    viewer, the bus or numpy).
    """
    from robomodel.cli._parser import Parser

    parser = Parser(
        prog="robomodel",
        description="URDF and xacro tools without ROS: check, graph, xacro, new, ...",
    )
    parser.add_argument("--version", action="version", version=_VERSION_TEXT)
    parser.add_argument("--debug", action="store_true", help="show Python tracebacks for errors")
    subparsers = parser.add_subparsers(dest="verb", metavar="COMMAND")
    subparsers.required = True
    for entry in VERBS:
        if verb is None or entry.name == verb:
            importlib.import_module(entry.module).register(subparsers)
        else:
            # Never parsed with: it only lists the verb (and add_help=False halves its cost).
            subparsers.add_parser(entry.name, help=entry.help, add_help=False)
    return parser


def _chosen_verb(args: Sequence[str]) -> str | None:
    """The verb named on the command line (the top-level options take no values), if any."""
    for index, arg in enumerate(args):
        if arg == "--":
            return args[index + 1] if index + 1 < len(args) else None
        if not arg.startswith("-"):
            return arg
    return None


def _terminal_safe(text: str) -> str:
    """``text`` with control characters other than line breaks spelt out (``\\x1b``): an error
    quotes arguments, file contents and names from peers, and a terminal would act on them."""
    if text.isprintable():
        return text
    from robomodel._escape import escape_name

    return "\n".join(
        line if line.isprintable() else "".join(escape_name(c) if c != "\\" else c for c in line)
        for line in text.split("\n")
    )


def _report(exc: RobomodelError) -> None:
    from robomodel.errors import InputError

    if isinstance(exc, InputError):
        print(_terminal_safe(exc.diagnostic.format()), file=sys.stderr)
        for note in exc.notes:
            print(_terminal_safe(note.format()), file=sys.stderr)
    else:
        print(_terminal_safe(f"robomodel: error: {exc}"), file=sys.stderr)


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised where the main thread is, so that every verb cleans up as for Ctrl-C."""


def _in_zenoh_callback(signum: int, frame: object) -> bool:
    """Whether the signal landed on a Zenoh callback's wrapper frame, where a raised exception
    would be swallowed by zenoh-python: it is then deferred until the callback returns."""
    zenoh_common = sys.modules.get("robomodel.runtime.transport._zenoh_common")
    if zenoh_common is None or getattr(frame, "f_code", None) is not zenoh_common.CALLBACK_CODE:
        return False
    zenoh_common.defer_signal(signum)
    return True


def _raise_interrupt(signum: int, frame: object) -> None:
    if not _in_zenoh_callback(signum, frame):
        raise KeyboardInterrupt


def _raise_terminated(signum: int, frame: object) -> None:
    if not _in_zenoh_callback(signum, frame):
        raise Terminated


def _install_signal_handlers() -> None:
    """Ctrl-C and SIGTERM end every verb through its ``finally`` blocks (children, files).

    Python installs its KeyboardInterrupt handler only when SIGINT is not ignored at start, and
    a script's ``robomodel view ... &`` starts with SIGINT ignored (a non-interactive shell
    ignores it for background jobs), so it is installed here whatever the start state was.
    SIGTERM's default action would end the process without cleanup (a ``<param command=>``
    tree left running): it raises :class:`Terminated` instead. Long-running verbs replace
    these with their own handlers while they run and put them back after.
    """
    import signal

    try:
        signal.signal(signal.SIGINT, _raise_interrupt)
        signal.signal(signal.SIGTERM, _raise_terminated)
    except ValueError:  # main() called from another thread: signals are not ours
        pass


def _unknown_verb(verb: str) -> int:
    """argparse's "invalid choice" with a did-you-mean (``robomodel lanch``)."""
    from robomodel.errors import describe_unknown

    message = describe_unknown("unknown command", verb, [v.name for v in VERBS], "commands are")
    print(f"robomodel: error: {message} (robomodel --help describes them)", file=sys.stderr)
    return EXIT_INVALID


def _parse(parser: argparse.ArgumentParser, args_list: list[str]) -> argparse.Namespace:
    """``parse_args``, except that ``name:=value`` may also come after options, as roslaunch,
    ``ros2 launch`` and xacro take it (``robomodel launch PKG FILE --headless gui:=false``):
    argparse leaves a positional after an option over, and such leftovers join the verb's
    ``name:=value`` list (``inputs`` or ``mappings``)."""
    args, extra = parser.parse_known_args(args_list)
    mappings = [item for item in extra if ":=" in item and not item.startswith("-")]
    target = next(
        (n for n in ("inputs", "mappings") if isinstance(getattr(args, n, None), list)), None
    )
    rest = [item for item in extra if item not in mappings or target is None]
    if rest:
        parser.error(f"unrecognized arguments: {' '.join(rest)}")
    if mappings and target is not None:
        getattr(args, target).extend(mappings)
    return args


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line and return its exit code."""
    args_list = list(sys.argv[1:] if argv is None else argv)
    if args_list == ["--version"]:
        # What argparse's version action prints, without loading argparse and its help
        # formatter (shutil, textwrap, locale): a third of the command's start-up.
        print(_VERSION_TEXT)
        return 0
    verb = _chosen_verb(args_list)
    if verb is not None and verb not in _VERB_NAMES:
        return _unknown_verb(verb)
    parser = build_parser(verb if verb in _VERB_NAMES else "")
    args = _parse(parser, args_list)
    if getattr(args, "type_package_path", None) or getattr(args, "distro", None):
        from robomodel.cli._types import apply_type_arguments

        apply_type_arguments(args)
    func: Callable[[argparse.Namespace], int] = args.func
    if argv is None:  # the command line, not a test calling main([...])
        _install_signal_handlers()
        code = _run_verb(func, args)
        _exit_if_a_bus_hangs(code)
        return code
    return _run_verb(func, args)


def _exit_if_a_bus_hangs(code: int) -> None:
    """End a process that loaded Zenoh without the interpreter's teardown, once its exit
    handlers have run: a Zenoh session whose close() never returned
    (robomodel.runtime.transport._zenoh_common.close_session) would keep it from exiting, and
    Zenoh's runtime threads, still running while the interpreter tears its statics down, can
    panic on the way out ("thread 'net-0' panicked ... static_init ... AccessError", seen once
    in a CI run after a one-line error), printing a Rust backtrace under the error."""
    zenoh_common = sys.modules.get("robomodel.runtime.transport._zenoh_common")
    abandoned = zenoh_common is not None and vars(zenoh_common).get("abandoned_sessions", 0)
    if "zenoh" not in sys.modules and not abandoned:
        return
    import atexit
    import contextlib
    import os

    atexit._run_exitfuncs()  # logging's flush, the GL contexts' release, ...
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):  # a closed pipe: nothing more to write
            stream.flush()
    os._exit(code)


def _run_verb(func: Callable[[argparse.Namespace], int], args: argparse.Namespace) -> int:
    """The verb's exit code; its errors as one line (exit 2), Ctrl-C 130, SIGTERM 143."""
    from robomodel.errors import RobomodelError

    try:
        return func(args)
    except RobomodelError as exc:
        if args.debug:
            raise
        _report(exc)
        return EXIT_INVALID
    except Terminated:
        return 143  # 128 + SIGTERM, as a process ended by the signal reports it
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        return 0


if __name__ == "__main__":
    sys.exit(main())
