"""``robomodel check``: check_urdf's output, then robomodel's located warnings."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from robomodel.cli._common import add_description_arguments, load_from_args
from robomodel.cli._verbs import verb_help
from robomodel.description.report import check_urdf_text
from robomodel.description.validate import validate_resources
from robomodel.errors import Diagnostic, InputError, Severity

__all__ = ["register"]

EXIT_OK = 0
EXIT_INVALID = 2


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "check",
        help=verb_help("check"),
        description=(
            "Parse and validate a robot description. On success stdout starts with exactly what "
            "urdfdom's check_urdf prints, followed by robomodel's extra warnings."
        ),
    )
    add_description_arguments(parser)
    parser.add_argument("--strict", action="store_true", help="treat warnings as errors")
    parser.add_argument("--json", action="store_true", help="print machine-readable diagnostics")
    parser.set_defaults(func=run)


def _as_error(diagnostic: Diagnostic) -> Diagnostic:
    return Diagnostic(Severity.ERROR, diagnostic.message, diagnostic.location, diagnostic.code)


def run(args: argparse.Namespace) -> int:
    try:
        result, loaded, index = load_from_args(args)
    except InputError as exc:
        if not args.json:
            raise
        _print_json(args.file, None, [exc.diagnostic, *exc.notes], valid=False)
        return EXIT_INVALID
    diagnostics = list(result.diagnostics)
    diagnostics += validate_resources(result.robot, index, loaded.base_dir)
    errors = any(d.severity is Severity.ERROR for d in diagnostics)
    valid = not errors and not (args.strict and diagnostics)
    if args.json:
        if args.strict:
            diagnostics = [_as_error(d) for d in diagnostics]
        _print_json(args.file, result, diagnostics, valid=valid)
        return EXIT_OK if valid else EXIT_INVALID
    sys.stdout.write(check_urdf_text(result.robot))
    if args.strict:
        for diagnostic in diagnostics:
            print(_as_error(diagnostic).format(), file=sys.stderr)
    else:
        for diagnostic in diagnostics:
            stream = sys.stderr if diagnostic.severity is Severity.ERROR else sys.stdout
            print(diagnostic.format(), file=stream)
    return EXIT_OK if valid else EXIT_INVALID


def _print_json(path: str, result: Any, diagnostics: list[Diagnostic], *, valid: bool) -> None:
    import json  # only for --json (start-up of the plain check)

    payload: dict[str, Any] = {"file": path, "valid": valid}
    if result is not None:
        robot = result.robot
        tree = robot.tree()
        payload.update(
            robot=robot.name,
            root=tree.root,
            links=len(robot.links),
            joints=len(robot.joints),
        )
    payload["diagnostics"] = [d.as_dict() for d in diagnostics]
    print(json.dumps(payload, indent=2))
