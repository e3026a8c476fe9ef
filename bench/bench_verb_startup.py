"""Start-up of every verb, this tree against an older one (a ``git worktree`` of a commit).

Run: ``.venv/bin/python bench/bench_verb_startup.py --old /tmp/oldtree [--rounds 15]``.
``--command "ARGS"`` (repeatable) times ``robomodel ARGS`` too, such as a command against a
graph you started; ``--commands-only`` leaves out the verbs' ``--help`` and the three commands.

For every verb both trees have, ``robomodel VERB --help`` (imports the verb's module and builds
its parser, which is what every run of the verb pays before it does its work), plus three real
commands (``--version``, ``check`` of a URDF, ``xacro`` of rrbot), run as pip's console script
runs robomodel, with byte-compiled modules, old and new interleaved round by round (the order
alternates). Prints the median wall time of each side and the ratio new / old as a markdown
table: whether a change kept every verb's start-up as it was.
"""

from __future__ import annotations

import argparse
import compileall
import os
import shlex
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
LAUNCHER = "import sys; from robomodel.cli.main import main; sys.exit(main())"


def _verbs(tree: Path) -> list[str]:
    code = "from robomodel.cli._verbs import VERBS; print(' '.join(v.name for v in VERBS))"
    out = subprocess.run(
        [sys.executable, "-c", code],
        env={**os.environ, "PYTHONPATH": str(tree / "src")},
        capture_output=True,
        text=True,
        check=True,
    )
    return out.stdout.split()


def _run_once(tree: Path, argv: list[str]) -> float:
    env = {**os.environ, "PYTHONPATH": str(tree / "src")}
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    start = time.perf_counter()
    subprocess.run(
        [sys.executable, "-c", LAUNCHER, *argv],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        check=False,
        cwd=REPO,
    )
    return (time.perf_counter() - start) * 1e3


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--old", type=Path, required=True, help="the older tree (a worktree)")
    parser.add_argument("--rounds", type=int, default=15)
    parser.add_argument("--command", action="append", default=[], help="more ARGS to time")
    parser.add_argument("--commands-only", action="store_true", help="time --command only")
    args = parser.parse_args()
    old: Path = args.old.resolve()
    for tree in (REPO, old):
        compileall.compile_dir(tree / "src" / "robomodel", quiet=1)
    common = [v for v in _verbs(REPO) if v in set(_verbs(old))]
    commands = [shlex.split(command) for command in args.command]
    if not args.commands_only:
        commands += [["--version"]]
        commands += [["check", "examples/gripper_description/urdf/planar_3dof.urdf"]]
        commands += [["xacro", "examples/rrbot_description/urdf/rrbot.xacro"]]
        commands += [[verb, "--help"] for verb in common]
    print(f"| command | before ({old.name}) | after | after / before |")
    print("|---|---|---|---|")
    ratios: list[float] = []
    for argv in commands:
        before: list[float] = []
        after: list[float] = []
        for index in range(args.rounds):
            pair = [(old, before), (REPO, after)]
            for tree, times in pair if index % 2 else reversed(pair):
                times.append(_run_once(tree, argv))
        b, a = statistics.median(before), statistics.median(after)
        ratios.append(a / b)
        label = " ".join(argv)
        print(f"| `robomodel {label}` | {b:.1f} ms | {a:.1f} ms | {a / b:.2f} |", flush=True)
    print(
        f"\nmedian ratio {statistics.median(ratios):.2f}, range {min(ratios):.2f}-{max(ratios):.2f}"
    )


if __name__ == "__main__":
    main()
