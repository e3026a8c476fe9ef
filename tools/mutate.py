"""Mutation testing of the core modules with mutmut, one module group at a time.

Each group is a few source files and the fast in-process tests that cover them. A group runs in
``build/mutate/GROUP/``, a folder of its own with links to ``src``, ``tests`` and ``examples``
and a ``pyproject.toml`` that is the project's plus a ``[tool.mutmut]`` table naming the
group's files and tests, since mutmut reads its settings from the current folder only. mutmut
records which tests reach each function and runs only those on that function's mutants, each
in a process forked from one that has imported everything, so a group's run is minutes where
running pytest anew per mutant would be hours.

The score per source file is printed as a Markdown table (the one in CONTRIBUTING.md) and
written to ``build/mutate/GROUP/scores.json``; ``--survivors`` prints each surviving mutant's
diff. Results are kept, so a second run of a group re-tests only what changed.

    python tools/mutate.py                  # every group, in order
    python tools/mutate.py inproc names     # these groups
    python tools/mutate.py --list           # the groups, their files and tests
    python tools/mutate.py master --again   # the survivors again, after new tests
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WORK = ROOT / "build" / "mutate"


@dataclass(frozen=True, slots=True)
class Group:
    """Source files (under src/robomodel/) and the tests (under tests/) that cover them."""

    name: str
    sources: tuple[str, ...]
    tests: tuple[str, ...]
    sample: int = 1


GROUPS = (
    Group(
        "inproc",
        ("runtime/transport/inproc.py",),
        (
            "runtime/test_inproc.py",
            # their other tests start Zenoh processes, which cannot import the mutated tree
            "runtime/test_services.py::test_inproc_service_call_and_errors",
            "runtime/test_services.py::test_an_inproc_service_answers_a_call_with_another_class_of_its_type",
            "runtime/test_subscription_count.py::test_inproc_counts_the_subscriptions_it_delivers_to",
        ),
    ),
    Group(
        "master",
        ("runtime/transport/ros1/master.py", "runtime/transport/ros1/names.py"),
        (
            "runtime/test_ros1_master.py",
            "runtime/test_ros1_master_hostile.py",
            "runtime/test_ros1_master_api.py",
            "runtime/test_ros1_names.py",
        ),
    ),
    Group(
        "rviz_io",
        ("viewer/displays/rviz_io.py",),
        (
            "viewer/test_display_qos.py",
            "viewer/test_displays_config.py",
            "viewer/test_rviz_save.py",
            "viewer/test_rviz_files.py",
            "viewer/test_displays_rviz.py",
            "viewer/test_sensor_displays_rviz.py",
        ),
        sample=5,
    ),
    Group(
        "rviz_files",
        (
            "viewer/rviz_yaml.py",
            "viewer/rviz_model.py",
            "viewer/rviz_config.py",
            "viewer/rviz_write.py",
            "viewer/rviz_document.py",
        ),
        (
            "viewer/test_rviz_files.py",
            "viewer/test_rviz_save.py",
            "viewer/test_displays_config.py",
        ),
        sample=10,
    ),
    Group(
        "bag_readers",
        ("bag/_mcap_reader.py", "bag/reader.py"),
        (
            "bag/test_bad_input.py",
            "bag/test_readers.py",
            "bag/test_sqlite3.py",
            "bag/test_typedefs.py",
        ),
        sample=5,
    ),
    Group(
        "cdr",
        (
            "runtime/msg/_cdr_encode.py",
            "runtime/msg/_cdr_decode.py",
            "runtime/msg/_cdr_strings.py",
            "runtime/msg/_cdr_codegen.py",
            "runtime/msg/cdr.py",
        ),
        (
            "runtime/test_messages.py",
            "runtime/test_cdr_float64.py",
            "runtime/test_cdr_strings.py",
            "runtime/test_types_from_definitions.py",
            "runtime/test_rmw_zenoh_wire.py",
        ),
        sample=10,
    ),
    Group(
        "ros1_codec",
        ("runtime/transport/ros1/ros1_codec.py",),
        (
            "runtime/test_ros1_messages.py",
            "runtime/test_types_from_definitions.py",
            "runtime/test_ros1_codec_oracle.py",
        ),
        sample=5,
    ),
    Group(
        "msg_defs",
        ("runtime/msg/definition.py", "runtime/msg/spec.py"),
        (
            "runtime/test_definition_parser.py",
            "runtime/test_definition_limits.py",
            "runtime/test_message_spec.py",
            "runtime/test_types_from_definitions.py",
        ),
        sample=10,
    ),
    Group(
        "msg_types",
        ("runtime/msg/typehash.py", "runtime/msg/schema.py", "runtime/msg/_from_definition.py"),
        (
            "runtime/test_type_hashes.py",
            "runtime/test_types_from_definitions.py",
            "runtime/test_type_descriptions.py",
            "runtime/test_types_rebuilt.py",
        ),
        sample=2,
    ),
    Group(
        "control_maths",
        ("control/pid.py", "control/controllers/trajectory.py", "control/controllers/odometry.py"),
        (
            "control/test_pid_bounds.py",
            "control/test_reference_scenarios.py",
            "control/test_controllers.py",
            "control/test_properties.py",
            "control/test_control_maths.py",
        ),
    ),
    Group(
        "diff_drive",
        ("control/controllers/diff_drive.py",),
        (
            "control/test_controllers.py",
            "control/test_control_maths.py",
            "control/test_diff_drive.py",
        ),
        sample=2,
    ),
)

# A group's ``sample`` of N tests every Nth mutant of each function (those whose number ends
# in a multiple of N: N is 1, 2, 5 or 10), chosen by name so that a second run picks the same
# ones; the score is then over the mutants tested. ``--sample`` sets it for one run.
SAMPLE_DIGITS = {1: "", 2: "02468", 5: "05", 10: "0"}

# The tests of a group run in mutmut's process, without xdist, and only the quick ones. A test
# that starts robomodel in a process of its own runs the unmutated code there, and one whose
# process does not come up waits for it for minutes: the process tier is left out.
PYTEST_ARGS = [
    "-p", "no:xdist", "-p", "no:cacheprovider", "-m", "not slow and not browser and not process"
]  # fmt: skip


def _toml_list(items: list[str]) -> str:
    return "[" + ", ".join(json.dumps(item) for item in items) + "]"


def prepare(group: Group) -> Path:
    """The group's folder: links to the tree and a pyproject.toml with its mutmut table."""
    folder = WORK / group.name
    folder.mkdir(parents=True, exist_ok=True)
    for name in ("src", "tests", "examples", "docs"):
        link = folder / name
        if not link.is_symlink():
            link.symlink_to(ROOT / name, target_is_directory=True)
    table = "\n".join(
        [
            "",
            "[tool.mutmut]",
            'source_paths = ["src"]',
            f"only_mutate = {_toml_list([f'src/robomodel/{s}' for s in group.sources])}",
            "pytest_add_cli_args_test_selection = "
            + _toml_list([f"tests/{t}" for t in group.tests]),
            f"pytest_add_cli_args = {_toml_list(PYTEST_ARGS)}",
            'also_copy = ["examples", "docs"]',
            "use_git_change_detection = false",
            # mutmut's default ("fork") runs the clean tests in its own process and forks each
            # mutant's from it: what those tests memoized (the generated CDR and ROS 1 codecs,
            # type hashes, cached specs) is inherited, made by the unmutated code, and no
            # mutant of the code that made it could fail a test. The fork server runs the
            # clean tests in a child of its own and forks the mutants' from a process that has
            # only collected the tests.
            'process_isolation = "forkserver"',
            # a mutant that makes a test wait (a queue, a thread) uses no CPU time: mutmut
            # ends it after this many times the tests' own duration
            "timeout_multiplier = 5.0",
            "",
        ]
    )
    (folder / "pyproject.toml").write_text(_without_xdist_options(ROOT / "pyproject.toml") + table)
    return folder


def _without_xdist_options(pyproject: Path) -> str:
    """The project's pyproject.toml with xdist's options (``--dist``, ``-n``) taken out of
    pytest's ``addopts``: the group's tests run with xdist off (``-p no:xdist``), and pytest
    refuses an option whose plugin is not loaded."""
    text = pyproject.read_text()
    line = re.search(r'^addopts = "(.*)"$', text, flags=re.M)
    if line is None:
        return text
    kept = re.sub(r"\s*(--dist|--numprocesses|-n)(=|\s+)\S+", "", line[1]).strip()
    return text[: line.start(1)] + kept + text[line.end(1) :]


def run(group: Group, *, children: int, again: bool = False, sample: int | None = None) -> int:
    """mutmut run in the group's folder; its exit code. ``again``: test the survivors and the
    mutants without tests anew (mutmut keeps a mutant's verdict until its function changes,
    so a new test is not tried on them otherwise). ``sample``: every Nth mutant only (the
    group's own when not given); mutmut tests a mutant named on its command line anew even
    when it has a verdict, so a sampled run tests its whole sample each time."""
    folder = prepare(group)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(ROOT / "src")  # mutmut puts mutants/src before it
    # robomodel-clientlibs.pth looks robomodel up at interpreter start, which would import the
    # unmutated tree before mutmut puts mutants/src first: no test would reach a mutant
    env["ROBOMODEL_CLIENTLIBS"] = "0"
    # no Zenoh router for the run, and no session linked to one (tests/conftest.py): the
    # groups' tests are in-process, and a session's threads in mutmut's fork server would not
    # survive its fork (every mutant's process hung until its timeout)
    env["ROBOMODEL_TEST_ROUTER"] = "0"
    command = [sys.executable, "-m", "mutmut", "run", "--max-children", str(children)]
    digits = SAMPLE_DIGITS[group.sample if sample is None else sample]
    if again:
        names = survivors(group, ("survived", "no tests"))
        if not names:
            return 0
    else:
        names = [f"*__mutmut_*{digit}" for digit in digits]
    # mutmut's forked processes end without pytest's unconfigure, which removes the folder
    # tests/conftest.py makes for the tests' processes: it is made in a folder of this run's
    # own (TMPDIR), removed when mutmut ends
    with tempfile.TemporaryDirectory(prefix="robomodel-mutate-") as scratch:
        env["TMPDIR"] = scratch
        return subprocess.run(command + names, cwd=folder, env=env, check=False).returncode


def scores(group: Group) -> dict[str, dict[str, int]]:
    """Per source file: how many of its mutants ended in each status."""
    from mutmut.stats import status_by_exit_code

    out: dict[str, dict[str, int]] = {}
    for source in group.sources:
        meta = WORK / group.name / "mutants" / "src" / "robomodel" / f"{source}.meta"
        counts: dict[str, int] = {}
        if meta.exists():
            for code in json.loads(meta.read_text())["exit_code_by_key"].values():
                status = status_by_exit_code[code]
                counts[status] = counts.get(status, 0) + 1
        out[source] = counts
    if (WORK / group.name).is_dir():  # a group never run here has no folder: nothing to keep
        (WORK / group.name / "scores.json").write_text(json.dumps(out, indent=2, sort_keys=True))
    return out


def survivors(group: Group, statuses: tuple[str, ...] = ("survived",)) -> list[str]:
    """The names of the group's mutants that ended in one of ``statuses``."""
    from mutmut.stats import status_by_exit_code

    names = []
    for source in group.sources:
        meta = WORK / group.name / "mutants" / "src" / "robomodel" / f"{source}.meta"
        if meta.exists():
            codes = json.loads(meta.read_text())["exit_code_by_key"]
            names += [k for k, c in codes.items() if status_by_exit_code[c] in statuses]
    return names


def table_row(group: str, source: str, counts: dict[str, int]) -> str:
    """A row of the scores table: the score is over the mutants tested so far."""
    killed = sum(counts.get(k, 0) for k in ("killed", "timeout", "segfault"))
    total = sum(counts.values())
    tested = total - counts.get("not checked", 0) - counts.get("check was interrupted by user", 0)
    score = f"{100 * killed / tested:.0f}%" if tested else "-"
    return (
        f"| {group} | `{source}` | {total} | {tested} | {killed} | {counts.get('survived', 0)} "
        f"| {counts.get('no tests', 0)} | {score} |"
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("groups", nargs="*", help="groups to run (default: all)")
    parser.add_argument("--list", action="store_true", help="show the groups and stop")
    parser.add_argument("--report", action="store_true", help="print the scores, run nothing")
    parser.add_argument("--survivors", action="store_true", help="print surviving mutants")
    parser.add_argument("--fresh", action="store_true", help="forget a group's earlier results")
    parser.add_argument(
        "--again", action="store_true", help="test the survivors and no-tests mutants anew"
    )
    parser.add_argument("--children", type=int, default=1, help="mutants tested at once")
    parser.add_argument(
        "--sample",
        type=int,
        choices=sorted(SAMPLE_DIGITS),
        help="test every Nth mutant of each function (default: the group's own, 1 for most)",
    )
    args = parser.parse_args(argv)
    by_name = {g.name: g for g in GROUPS}
    unknown = [name for name in args.groups if name not in by_name]
    if unknown:
        print(
            f"mutate: unknown group {', '.join(unknown)}; groups are: {', '.join(by_name)}",
            file=sys.stderr,
        )
        return 2
    chosen = [by_name[name] for name in args.groups] or list(GROUPS)
    if args.list:
        for g in chosen:
            sampled = f" (1 mutant in {g.sample})" if g.sample > 1 else ""
            print(f"{g.name}{sampled}: {', '.join(g.sources)}\n    tests: {', '.join(g.tests)}")
        return 0
    failed = []
    for g in chosen:
        if not args.report:
            if args.fresh:
                shutil.rmtree(WORK / g.name / "mutants", ignore_errors=True)
            if run(g, children=args.children, again=args.again, sample=args.sample) != 0:
                failed.append(g.name)
    print("\n| group | module | mutants | tested | killed | survived | no tests | score |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for g in chosen:
        for source, counts in scores(g).items():
            print(table_row(g.name, source, counts))
    if args.survivors:
        for g in chosen:
            for name in survivors(g):
                shown = subprocess.run(
                    [sys.executable, "-m", "mutmut", "show", name],
                    cwd=WORK / g.name, capture_output=True, text=True, check=False,
                )  # fmt: skip
                print(shown.stdout)
    if failed:
        print(f"mutate: mutmut failed for {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
