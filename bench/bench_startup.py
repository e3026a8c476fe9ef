"""Start-up: whole ``robomodel`` processes against the commands a ROS user would run instead.

Each group runs its commands interleaved, ``--rounds`` times (the order rotates every round so
that neither side always runs first on a warm cache), and prints the median wall time of each
process and the ratio of the medians. Before timing, the outputs are compared where both sides
print the same thing (xacro: byte-identical URDF).

Groups:
  * ``robomodel xacro FILE`` vs ROS xacro 2.1.1's ``xacro FILE`` (the PyPI package of the test
    extra, its console script next to this Python) on every ``examples/*/urdf/*.xacro`` and on
    the PR2 of the reference's sdist (``test/robots/pr2``). ``$(find PKG)`` resolves for both
    through one ament prefix made for the run (``AMENT_PREFIX_PATH``; the reference reads it
    with Debian's ``python3-ament-index``, which the ROS 2 xacro needs, as on a ROS system).
    Target: ratio <= 0.7.
  * ``robomodel check FILE`` vs ``python -c "import lxml.etree"`` (target: <= 3) and urdfdom's
    ``check_urdf`` (Debian's liburdfdom-tools, given the expanded URDF for a .xacro).
  * ``robomodel --version`` vs ``python -c pass`` (target: <= 1.5).
  * Any Python of the environment, with ``ROS_PACKAGE_PATH`` set as in a ROS user's shell and
    with it empty: ``python -c "import copy, subprocess, mimetypes"`` with robomodel's
    client-library finder (installed at start by its ``.pth`` file; the standard library's
    failed imports of other platforms' modules reach it) against the same with it switched
    off (``ROBOMODEL_CLIENTLIBS=0``). What installing robomodel costs every Python start.

``robomodel`` is run as pip's generated console script runs it (``from robomodel.cli.main
import main; sys.exit(main())``), written to a temporary directory with this interpreter and
``src/`` first on ``PYTHONPATH``; a user's installed copy has byte-compiled modules, so the run
drops ``PYTHONDONTWRITEBYTECODE`` and byte-compiles ``src/robomodel`` first.

Usage:
    python bench/bench_startup.py [--rounds N] [--pr2 DIR] [--only xacro|check|version|python]

``--pr2 DIR`` is the unpacked ``xacro-2.1.1`` sdist; without it the sdist is fetched with
``pip download --no-deps --no-binary :all: xacro==2.1.1`` (the PR2 is skipped if that fails).
"""

from __future__ import annotations

import argparse
import compileall
import os
import shutil
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
EXAMPLES = REPO / "examples"
AMENT_INDEX_PYTHON = Path("/usr/lib/python3/dist-packages/ament_index_python")
CHECK_URDF = shutil.which("check_urdf") or "/usr/bin/check_urdf"

CONSOLE_SCRIPT = """#!{python}
import sys
from robomodel.cli.main import main
if __name__ == '__main__':
    sys.argv[0] = sys.argv[0].removesuffix('.exe')
    sys.exit(main())
"""


@dataclass(frozen=True, slots=True)
class Command:
    label: str
    argv: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class Setup:
    """Where the commands live and the environment both sides run in."""

    robomodel: str
    xacro: str | None
    env: dict[str, str]
    tmp: Path


def _run(argv: tuple[str, ...], env: dict[str, str]) -> subprocess.CompletedProcess[bytes]:
    return subprocess.run(argv, capture_output=True, env=env, check=False)


def _time_s(argv: tuple[str, ...], env: dict[str, str]) -> float:
    start = time.perf_counter()
    subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env, check=False)
    return time.perf_counter() - start


def race(title: str, baseline: Command, others: list[Command], setup: Setup, rounds: int) -> None:
    """Time ``baseline`` and ``others`` interleaved; print medians and ratios to the baseline."""
    commands = [baseline, *others]
    times: list[list[float]] = [[] for _ in commands]
    for index in range(len(commands)):  # warm-up: page cache, .pyc files
        _time_s(commands[index].argv, setup.env)
    for round_index in range(rounds):
        shift = round_index % len(commands)
        for index in [*range(shift, len(commands)), *range(shift)]:
            times[index].append(_time_s(commands[index].argv, setup.env))
    base = statistics.median(times[0])
    print(f"  {title}")
    for command, samples in zip(commands, times, strict=True):
        median = statistics.median(samples)
        print(f"    {median * 1e3:8.1f} ms  {median / base:5.2f}x  {command.label}")


def prepare(tmp: Path, pr2: Path | None) -> Setup:
    """The console script, the ament prefix of the examples (and xacro's sdist), the env."""
    script = tmp / "bin" / "robomodel"
    script.parent.mkdir()
    script.write_text(CONSOLE_SCRIPT.format(python=sys.executable))
    script.chmod(0o755)
    prefix = tmp / "prefix"
    markers = prefix / "share" / "ament_index" / "resource_index" / "packages"
    markers.mkdir(parents=True)
    packages = {p.parent.name: p.parent for p in EXAMPLES.glob("*/package.xml")}
    if pr2 is not None:
        packages["xacro"] = pr2
    for name, source in packages.items():
        (prefix / "share" / name).symlink_to(source)
        (markers / name).touch()
    python_path = [str(REPO / "src")]
    if AMENT_INDEX_PYTHON.is_dir():
        shim = tmp / "ament"  # only ament_index_python, not the whole of Debian's dist-packages
        shim.mkdir()
        (shim / AMENT_INDEX_PYTHON.name).symlink_to(AMENT_INDEX_PYTHON)
        python_path.append(str(shim))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPATH"] = os.pathsep.join(python_path)
    env["AMENT_PREFIX_PATH"] = str(prefix)
    env.pop("ROS_PACKAGE_PATH", None)
    compileall.compile_dir(REPO / "src" / "robomodel", quiet=1)
    xacro = Path(sys.executable).with_name("xacro")
    return Setup(str(script), str(xacro) if xacro.exists() else None, env, tmp)


def fetch_pr2(tmp: Path) -> Path | None:
    """Unpack xacro 2.1.1's sdist (its test/robots/pr2) into ``tmp``."""
    download = [sys.executable, "-m", "pip", "download", "--quiet", "--no-deps"]
    download += ["--no-binary", ":all:", "xacro==2.1.1", "-d", str(tmp)]
    if subprocess.run(download, capture_output=True, check=False).returncode != 0:
        return None
    with tarfile.open(tmp / "xacro-2.1.1.tar.gz") as archive:
        archive.extractall(tmp, filter="data")
    return tmp / "xacro-2.1.1"


def bench_xacro(setup: Setup, pr2: Path | None, rounds: int) -> None:
    print("robomodel xacro FILE vs ROS xacro 2.1.1 `xacro FILE` (target: ratio <= 0.7)")
    if setup.xacro is None:
        print("  skipped: the reference's console script is missing (pip install xacro==2.1.1)")
        return
    files = sorted(EXAMPLES.glob("*/urdf/*.xacro"))
    if pr2 is not None:
        files.append(pr2 / "test" / "robots" / "pr2" / "pr2.urdf.xacro")
    for path in files:
        reference = Command("xacro (ROS, 2.1.1)", (setup.xacro, str(path)))
        ours = Command("robomodel xacro", (setup.robomodel, "xacro", str(path)))
        expected, actual = _run(reference.argv, setup.env), _run(ours.argv, setup.env)
        if expected.returncode != 0:
            print(f"  {path.name}: reference failed, skipped: {expected.stderr[-200:]!r}")
            continue
        same = expected.stdout == actual.stdout and actual.returncode == 0
        size = f"{len(actual.stdout) / 1024:.1f} KiB"
        label = f"{path.relative_to(path.parents[2])} ({size}, "
        label += "identical output)" if same else "OUTPUT DIFFERS)"
        race(label, reference, [ours], setup, rounds)


def bench_check(setup: Setup, rounds: int) -> None:
    print("robomodel check FILE vs python -c 'import lxml.etree' (target <= 3x) and check_urdf")
    files = sorted(EXAMPLES.glob("*/urdf/*.urdf")) + sorted(EXAMPLES.glob("*/urdf/*.urdf.xacro"))
    lxml = Command("python -c 'import lxml.etree'", (sys.executable, "-c", "import lxml.etree"))
    for path in files:
        ours = Command("robomodel check", (setup.robomodel, "check", str(path)))
        result = _run(ours.argv, setup.env)
        others = [ours]
        if Path(CHECK_URDF).exists():
            urdf = path
            if path.suffix == ".xacro":  # check_urdf reads URDF only: give it the expansion
                urdf = setup.tmp / (path.stem + ".expanded.urdf")
                expanded = _run((setup.robomodel, "xacro", str(path)), setup.env)
                urdf.write_bytes(expanded.stdout)
            others.append(Command("check_urdf (urdfdom)", (CHECK_URDF, str(urdf))))
        status = "ok" if result.returncode == 0 else f"exit {result.returncode}"
        race(f"{path.relative_to(path.parents[2])} ({status})", lxml, others, setup, rounds)


def bench_version(setup: Setup, rounds: int) -> None:
    print("robomodel --version vs python -c pass (target <= 1.5x)")
    version = Command("robomodel --version", (setup.robomodel, "--version"))
    baseline = Command("python -c pass", (sys.executable, "-c", "pass"))
    race("--version", baseline, [version], setup, rounds)


def bench_python(setup: Setup, rounds: int) -> None:
    code = "import copy, subprocess, mimetypes"
    unset = ("-u", "ROS_PACKAGE_PATH", "-u", "AMENT_PREFIX_PATH")
    for what, paths in (
        ("ROS_PACKAGE_PATH set", (*unset, f"ROS_PACKAGE_PATH={EXAMPLES}")),
        # Debian's ROS packages install to /usr/share, among every other package's data
        (
            "ROS_PACKAGE_PATH holding /usr/share",
            (*unset, f"ROS_PACKAGE_PATH={EXAMPLES}:/usr/share"),
        ),
        ("no package path", unset),
    ):
        print(f"python with {what}: robomodel's import finder on vs off")

        def python(finder: str, paths: tuple[str, ...] = paths) -> tuple[str, ...]:
            # env(1) on both sides, so that both pay its exec
            return ("env", *paths, f"ROBOMODEL_CLIENTLIBS={finder}", sys.executable, "-c", code)

        race(
            f"python -c '{code}'",
            Command("finder off (ROBOMODEL_CLIENTLIBS=0)", python("0")),
            [Command("finder on (as installed)", python("1"))],
            setup,
            rounds,
        )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--rounds", type=int, default=20)
    parser.add_argument("--pr2", type=Path, help="the unpacked xacro-2.1.1 sdist directory")
    parser.add_argument("--only", choices=("xacro", "check", "version", "python"))
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="bench_startup_") as tmp_name:
        tmp = Path(tmp_name)
        pr2 = args.pr2
        if pr2 is None and args.only in (None, "xacro"):
            pr2 = fetch_pr2(tmp)
            if pr2 is None:
                print("PR2 skipped: could not download the xacro 2.1.1 sdist")
        setup = prepare(tmp, pr2)
        if not AMENT_INDEX_PYTHON.is_dir():
            print("note: Debian's python3-ament-index is missing; the reference cannot $(find)")
        print(f"rounds: {args.rounds}; medians of whole-process wall time\n")
        if args.only in (None, "version"):
            bench_version(setup, args.rounds)
        if args.only in (None, "python"):
            bench_python(setup, args.rounds)
        if args.only in (None, "check"):
            bench_check(setup, args.rounds)
        if args.only in (None, "xacro"):
            bench_xacro(setup, pr2, args.rounds)
    return 0


if __name__ == "__main__":
    sys.exit(main())
