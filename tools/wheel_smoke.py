"""Build robomodel's wheel and smoke-test it under every Python the package claims (3.10-3.13).

The wheel is built once, from a copy of the checkout's package files (so the build leaves
nothing in the checkout). For each interpreter found, a fresh venv under build/wheel-smoke/ gets
the wheel (not an editable install) with the ``sim`` and ``bus`` extras, and runs one command of
each verb family from a temporary folder outside the checkout, so nothing of src/ can be
imported by accident: check, xacro, fk, new, sim (headless, a second of sim time), and a launch
on Zenoh whose /joint_states another process echoes. The interpreters run side by side, and so
do the verb families of each.

venvs and installs go through uv (the ``test`` extra), which makes a venv in a fraction of a
second and installs from one cache shared by all the interpreters; a wheel it has unpacked once
it links in again. Interpreters: ``--python PATH ...``, else ``python3.N`` on PATH or pyenv's
``~/.pyenv/versions/3.N.*``; a claimed version with none is reported, not failed
(``--require-all`` fails it). ``make test`` runs this as tests/test_wheel_smoke.py.

    python tools/wheel_smoke.py                  # make wheel-smoke
    python tools/wheel_smoke.py --python /usr/bin/python3.12
"""

from __future__ import annotations

import argparse
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "build" / "wheel-smoke"
CLAIMED = ("3.10", "3.11", "3.12", "3.13")
EXTRAS = "sim,bus"
# What the wheel is built from: the package's sources and the files pyproject.toml names.
BUILD_INPUTS = ("pyproject.toml", "setup.py", "README.md", "src")
# The environment a user's shell would not have: the checkout's or the test run's.
_DROPPED_ENV = (
    "PYTHONPATH", "VIRTUAL_ENV", "ROS_PACKAGE_PATH", "ROS_MASTER_URI", "PYTHONHOME",
    "PYTHONDONTWRITEBYTECODE", "PYTHONPYCACHEPREFIX",
)  # fmt: skip


class SmokeError(Exception):
    """A step of the smoke failed: ``step`` names it, the message shows the command's output."""

    def __init__(self, step: str, message: str) -> None:
        self.step = step
        super().__init__(message)


@dataclass(frozen=True, slots=True)
class Outcome:
    """What one interpreter's smoke did: seconds per step (in the order they ended) and the
    failed steps with their messages."""

    minor: str
    python: Path
    seconds_by_step: tuple[tuple[str, float], ...]
    failures: tuple[tuple[str, str], ...]
    total_s: float


def find_pythons() -> dict[str, Path]:
    """Claimed minor version -> an interpreter of it on this machine (its real executable, not
    a pyenv shim)."""
    found: dict[str, Path] = {}
    pyenv = Path(os.environ.get("PYENV_ROOT", Path.home() / ".pyenv")) / "versions"
    for minor in CLAIMED:
        on_path = shutil.which(f"python{minor}")
        candidates = [Path(on_path)] if on_path else []
        candidates += sorted(pyenv.glob(f"{minor}.*/bin/python{minor}"), reverse=True)
        for candidate in candidates:
            version, executable = _identify(candidate)
            if version == minor and executable is not None:
                found[minor] = executable
                break
    return found


def _identify(python: Path) -> tuple[str | None, Path | None]:
    """(``3.N``, the interpreter's own executable) of ``python``, or (None, None)."""
    try:
        done = subprocess.run(
            [str(python), "-c",
             "import sys; print('%d.%d' % sys.version_info[:2]); print(sys.executable)"],
            capture_output=True, text=True, timeout=60,
        )  # fmt: skip
    except (OSError, subprocess.TimeoutExpired):
        return None, None
    lines = done.stdout.split()
    if done.returncode != 0 or len(lines) != 2:
        return None, None
    return lines[0], Path(lines[1])


def find_uv() -> Path:
    """uv beside this interpreter (the venv's, from the ``test`` extra), else on PATH."""
    beside = shutil.which("uv", path=str(Path(sys.executable).parent))
    found = beside or shutil.which("uv")
    if found is None:
        raise SystemExit(
            "wheel-smoke: needs uv (in robomodel's test extra): pip install 'robomodel[test]'"
        )
    return Path(found)


def _run(
    step: str, argv: list[str], *, cwd: Path, env: dict[str, str], timeout_s: float = 600
) -> str:
    try:
        done = subprocess.run(
            argv, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout_s
        )
    except subprocess.TimeoutExpired as exc:
        raise SmokeError(step, f"`{' '.join(argv)}` did not end in {timeout_s:.0f} s") from exc
    if done.returncode != 0:
        raise SmokeError(
            step, f"`{' '.join(argv)}` exited {done.returncode}:\n{done.stdout}{done.stderr}"
        )
    return done.stdout


def build_wheel(uv: Path) -> Path:
    """The wheel of the checkout as it is (committed or not), built by uv in an isolated
    build environment from a copy of :data:`BUILD_INPUTS`."""
    wheels = OUT / "wheel"
    shutil.rmtree(wheels, ignore_errors=True)
    with tempfile.TemporaryDirectory(prefix="robomodel-wheel-") as tmp:
        source = Path(tmp)
        for name in BUILD_INPUTS:
            if (ROOT / name).is_dir():
                ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info")
                shutil.copytree(ROOT / name, source / name, ignore=ignore)
            else:
                shutil.copy2(ROOT / name, source / name)
        argv = [str(uv), "build", "--quiet", "--wheel", "--out-dir", str(wheels), str(source)]
        _run("build", argv, cwd=source, env=dict(os.environ))
    (wheel,) = wheels.glob("robomodel-*.whl")
    return wheel


class _Steps:
    """The seconds and failures of one interpreter's steps, recorded from several threads."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self.seconds: list[tuple[str, float]] = []
        self.failures: list[tuple[str, str]] = []

    def run(self, family: str, body: Callable[[], None]) -> bool:
        """Run ``body`` as ``family``; a failure is recorded (the step it names), not raised."""
        start = time.monotonic()
        try:
            body()
        except SmokeError as exc:
            with self._lock:
                self.failures.append((exc.step, str(exc)))
            return False
        with self._lock:
            self.seconds.append((family, time.monotonic() - start))
        return True


def smoke(minor: str, python: Path, wheel: Path, uv: Path, domain_id: str) -> Outcome:
    """Install ``wheel`` into a fresh venv of ``python`` and run the verb families."""
    start = time.monotonic()
    steps = _Steps()
    venv = OUT / f"py{minor}"
    shutil.rmtree(venv, ignore_errors=True)
    env = {k: v for k, v in os.environ.items() if k not in _DROPPED_ENV}
    env_python = str(venv / "bin" / "python")

    def install() -> None:
        _run("venv", [str(uv), "venv", "--quiet", "--python", str(python), str(venv)],
             cwd=OUT, env=env)  # fmt: skip
        _run("install", [str(uv), "pip", "install", "--quiet", "--python", env_python,
                         f"{wheel}[{EXTRAS}]"], cwd=OUT, env=env, timeout_s=1800)  # fmt: skip

    if not steps.run("venv+install", install):
        return _outcome(minor, python, steps, start)
    with tempfile.TemporaryDirectory(prefix=f"robomodel-smoke-{minor}-") as tmp:
        work = Path(tmp)
        shutil.copytree(ROOT / "examples", work / "examples")
        if steps.run("import", lambda: _imports(env_python, work, venv, env)):
            families = _families(str(venv / "bin" / "robomodel"), work, env, domain_id)
            with ThreadPoolExecutor(len(families)) as pool:
                list(pool.map(lambda item: steps.run(*item), families.items()))
    return _outcome(minor, python, steps, start)


def _outcome(minor: str, python: Path, steps: _Steps, start: float) -> Outcome:
    return Outcome(minor, python, tuple(steps.seconds), tuple(steps.failures),
                   time.monotonic() - start)  # fmt: skip


def _imports(env_python: str, work: Path, venv: Path, env: dict[str, str]) -> None:
    """Every module of the installed package compiles under this Python (syntax newer than it
    fails here, in modules no verb imports too; the verbs then share the byte code), robomodel
    imports from the venv, and robomodel-clientlibs.pth lets ROS's message modules import
    there with no build step."""
    (package,) = venv.glob("lib/python*/site-packages/robomodel")
    _run("compile", [env_python, "-m", "compileall", "-q", str(package)], cwd=work, env=env)
    where = _run("import", [env_python, "-c", "import robomodel; print(robomodel.__file__)"],
                 cwd=work, env=env)  # fmt: skip
    if not where.startswith(str(venv)):
        raise SmokeError("import", f"robomodel imported from {where.strip()}, not from the venv")
    face = _run("import", [env_python, "-c",
                           "from std_msgs.msg import String; print(repr(String(data='x')))"],
                cwd=work, env=env)  # fmt: skip
    if face.strip() != "std_msgs.msg.String(data='x')":
        raise SmokeError("import", f"std_msgs.msg did not import from the wheel's finder: {face!r}")


def _families(
    exe: str, work: Path, env: dict[str, str], domain_id: str
) -> dict[str, Callable[[], None]]:
    """The verb families, each a callable running its commands in ``work`` one after the other
    (the families of one interpreter run side by side)."""
    urdf = "examples/gripper_description/urdf/planar_3dof.urdf"

    def run(step: str, *args: str) -> str:
        return _run(step, [exe, *args], cwd=work, env=env, timeout_s=300)

    def check() -> None:
        if not run("check", "check", urdf).startswith("robot name is: planar_3dof"):
            raise SmokeError("check", "check printed something else than check_urdf's first line")

    def xacro() -> None:
        run("xacro", "xacro", "examples/gripper_description/urdf/planar_3dof.xacro", "-o", "x.urdf")
        run("xacro", "check", "x.urdf")

    def fk() -> None:
        out = run("fk", "fk", urdf, "--joint", "joint_1=0.5", "--link", "gripper")
        if "gripper" not in out:
            raise SmokeError("fk", f"fk printed no pose of the gripper:\n{out}")

    def sim() -> None:
        report = run("sim", "sim", "examples/rrbot_description/urdf/rrbot.xacro",
                     "--package-path", "examples", "--headless", "--bus", "inproc",
                     "--rate", "max", "--duration", "1", "--report", "json")  # fmt: skip
        if '"sim_time_s"' not in report:
            raise SmokeError("sim", f"sim printed no JSON report:\n{report}")

    def new_and_launch() -> None:
        run("new", "new", "smoke_description", "--dir", "ws")
        _launch_and_echo(exe, work, env, domain_id)

    return {"check": check, "xacro": xacro, "fk": fk, "sim": sim, "new+launch": new_and_launch}


def _launch_and_echo(exe: str, work: Path, env: dict[str, str], domain_id: str) -> None:
    """A ROS 1 launch file on Zenoh, its /joint_states echoed by another process."""
    log = (work / "launch.log").open("w")
    launch = subprocess.Popen(
        [exe, "launch", "smoke_description", "display.launch", "gui:=false", "--headless",
         "--package-path", "ws", "--domain-id", domain_id],
        cwd=work, env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
    )  # fmt: skip
    try:
        try:
            echo = subprocess.run(
                [exe, "topic", "echo", "/joint_states", "--once", "--domain-id", domain_id],
                cwd=work, env=env, capture_output=True, text=True, timeout=300,
            )  # fmt: skip
        except subprocess.TimeoutExpired as exc:
            raise SmokeError(
                "launch", f"topic echo /joint_states heard nothing in 300 s; launch log:\n"
                f"{(work / 'launch.log').read_text()}"
            ) from exc  # fmt: skip
        if echo.returncode != 0 or "joint_1" not in echo.stdout:
            raise SmokeError(
                "launch",
                f"topic echo /joint_states over Zenoh failed:\n{echo.stdout}{echo.stderr}\n"
                f"launch log:\n{(work / 'launch.log').read_text()}",
            )
    finally:
        if launch.poll() is None:
            os.killpg(launch.pid, signal.SIGINT)
            try:
                launch.wait(60)
            except subprocess.TimeoutExpired:
                os.killpg(launch.pid, signal.SIGKILL)
                launch.wait()
        log.close()


def _report(outcome: Outcome) -> str:
    steps = ", ".join(f"{name} {seconds:.1f} s" for name, seconds in outcome.seconds_by_step)
    head = f"wheel-smoke: Python {outcome.minor} ({outcome.python})"
    if not outcome.failures:
        return f"{head}: passed in {outcome.total_s:.0f} s ({steps})"
    failed = "".join(f"\n{head}: {step} FAILED: {message}" for step, message in outcome.failures)
    return f"{head}: FAILED in {outcome.total_s:.0f} s (passed: {steps or 'nothing'}){failed}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--python", nargs="+", type=Path, help="interpreters (default: found)")
    parser.add_argument(
        "--require-all", action="store_true", help="fail if a claimed Python is missing"
    )
    parser.add_argument(
        "--domain-ids", nargs="+", metavar="ID",
        help="Zenoh domain ids for the launches, one per interpreter (default: random in 150-229)",
    )  # fmt: skip
    args = parser.parse_args(argv)
    OUT.mkdir(parents=True, exist_ok=True)
    if args.python:
        pythons: dict[str, Path] = {}
        for given in args.python:
            minor, executable = _identify(given)
            pythons[minor or str(given)] = executable or given
    else:
        pythons = find_pythons()
        missing = [m for m in CLAIMED if m not in pythons]
        if missing:
            print(f"wheel-smoke: no Python {', '.join(missing)} on this machine", file=sys.stderr)
            if args.require_all:
                return 1
    domains = args.domain_ids or [str(d) for d in random.sample(range(150, 230), len(pythons))]
    if len(domains) < len(pythons):
        parser.error(f"--domain-ids: {len(pythons)} interpreters need as many ids")
    uv = find_uv()
    start = time.monotonic()
    try:
        wheel = build_wheel(uv)
    except SmokeError as exc:
        print(f"wheel-smoke: building the wheel FAILED: {exc}", file=sys.stderr, flush=True)
        return 1
    print(f"wheel-smoke: built {wheel.name} in {time.monotonic() - start:.1f} s", flush=True)
    with ThreadPoolExecutor(len(pythons)) as pool:
        runs = [
            pool.submit(smoke, minor, python, wheel, uv, domain)
            for (minor, python), domain in zip(sorted(pythons.items()), domains, strict=False)
        ]
        outcomes = [run.result() for run in runs]
    for outcome in outcomes:
        print(_report(outcome), file=sys.stderr if outcome.failures else sys.stdout, flush=True)
    failed = [o.minor for o in outcomes if o.failures]
    verdict = f"FAILED under Python {', '.join(failed)}" if failed else "passed"
    print(f"wheel-smoke: {verdict}, {time.monotonic() - start:.0f} s in all", flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
