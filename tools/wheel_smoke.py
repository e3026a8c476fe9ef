"""Build robomodel's wheel and smoke-test it under every Python the package claims (3.10-3.13).

For each interpreter found, a fresh venv under build/wheel-smoke/ gets the wheel (not an
editable install) with the ``sim`` and ``bus`` extras, and runs one command of each verb family
from a temporary folder outside the checkout, so nothing of src/ can be imported by accident:
check, xacro, fk, new, sim (headless, a second of sim time), and a launch on Zenoh whose
/joint_states another process echoes. Interpreters: ``--python PATH ...``, else ``python3.N`` on
PATH or pyenv's ``~/.pyenv/versions/3.N.*``; a claimed version with none is reported, not
failed (``--require-all`` fails it).

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
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "build" / "wheel-smoke"
CLAIMED = ("3.10", "3.11", "3.12", "3.13")
EXTRAS = "sim,bus"


class SmokeError(Exception):
    """A step of the smoke failed; the message says which and shows its output."""


def find_pythons() -> dict[str, Path]:
    """Claimed minor version -> an interpreter of it on this machine."""
    found: dict[str, Path] = {}
    pyenv = Path(os.environ.get("PYENV_ROOT", Path.home() / ".pyenv")) / "versions"
    for minor in CLAIMED:
        on_path = shutil.which(f"python{minor}")
        candidates = [Path(on_path)] if on_path else []
        candidates += sorted(pyenv.glob(f"{minor}.*/bin/python{minor}"), reverse=True)
        for candidate in candidates:
            if _version(candidate) == minor:
                found[minor] = candidate
                break
    return found


def _version(python: Path) -> str | None:
    try:
        done = subprocess.run(
            [str(python), "-c", "import sys; print('%d.%d' % sys.version_info[:2])"],
            capture_output=True, text=True, timeout=60,
        )  # fmt: skip
    except (OSError, subprocess.TimeoutExpired):
        return None
    return done.stdout.strip() if done.returncode == 0 else None


def _run(argv: list[str], *, cwd: Path, env: dict[str, str], timeout_s: float = 600) -> str:
    done = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout_s)
    if done.returncode != 0:
        raise SmokeError(
            f"`{' '.join(argv)}` exited {done.returncode}:\n{done.stdout}{done.stderr}"
        )
    return done.stdout


def build_wheel() -> Path:
    wheels = OUT / "wheel"
    shutil.rmtree(wheels, ignore_errors=True)
    _run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps", "-w", str(wheels), str(ROOT)],
         cwd=ROOT, env=dict(os.environ))  # fmt: skip
    (wheel,) = wheels.glob("robomodel-*.whl")
    return wheel


def smoke(minor: str, python: Path, wheel: Path) -> float:
    """Install ``wheel`` into a fresh venv of ``python`` and run the verbs; returns seconds."""
    start = time.monotonic()
    venv = OUT / f"py{minor}"
    shutil.rmtree(venv, ignore_errors=True)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env.pop("ROS_PACKAGE_PATH", None)
    env.pop("ROS_MASTER_URI", None)
    _run([str(python), "-m", "venv", str(venv)], cwd=OUT, env=env)
    pip = [str(venv / "bin" / "python"), "-m", "pip", "install", "--quiet"]
    _run([*pip, f"{wheel}[{EXTRAS}]"], cwd=OUT, env=env, timeout_s=1800)
    exe = str(venv / "bin" / "robomodel")
    with tempfile.TemporaryDirectory(prefix=f"robomodel-smoke-{minor}-") as tmp:
        work = Path(tmp)
        shutil.copytree(ROOT / "examples", work / "examples")
        urdf = "examples/gripper_description/urdf/planar_3dof.urdf"
        where = _run([str(venv / "bin" / "python"), "-c", "import robomodel; print(robomodel.__file__)"],
                     cwd=work, env=env)  # fmt: skip
        if not where.startswith(str(venv)):
            raise SmokeError(f"robomodel imported from {where.strip()}, not from the venv")
        # robomodel-clientlibs.pth: ROS's message modules import in the venv with no build step
        face = _run([str(venv / "bin" / "python"), "-c",
                     "from std_msgs.msg import String; print(repr(String(data='x')))"],
                    cwd=work, env=env)  # fmt: skip
        if face.strip() != "std_msgs.msg.String(data='x')":
            raise SmokeError(f"std_msgs.msg did not import from the wheel's finder: {face!r}")
        if not _run([exe, "check", urdf], cwd=work, env=env).startswith(
            "robot name is: planar_3dof"
        ):
            raise SmokeError("check printed something else than check_urdf's first line")
        _run([exe, "xacro", "examples/gripper_description/urdf/planar_3dof.xacro", "-o", "x.urdf"],
             cwd=work, env=env)  # fmt: skip
        _run([exe, "check", "x.urdf"], cwd=work, env=env)
        _run([exe, "fk", urdf, "--joint", "joint_1=0.5", "--link", "gripper"], cwd=work, env=env)
        _run([exe, "new", "smoke_description", "--dir", "ws"], cwd=work, env=env)
        report = _run([exe, "sim", "examples/rrbot_description/urdf/rrbot.xacro",
                       "--package-path", "examples", "--headless", "--bus", "inproc",
                       "--rate", "max", "--duration", "1", "--report", "json"],
                      cwd=work, env=env)  # fmt: skip
        if '"sim_time_s"' not in report:
            raise SmokeError(f"sim printed no JSON report:\n{report}")
        _launch_and_echo(exe, work, env)
    return time.monotonic() - start


def _launch_and_echo(exe: str, work: Path, env: dict[str, str]) -> None:
    """A ROS 1 launch file on Zenoh, its /joint_states echoed by another process."""
    domain = str(random.randint(150, 229))
    log = (work / "launch.log").open("w")
    launch = subprocess.Popen(
        [exe, "launch", "smoke_description", "display.launch", "gui:=false", "--headless",
         "--package-path", "ws", "--domain-id", domain],
        cwd=work, env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
    )  # fmt: skip
    try:
        echo = subprocess.run(
            [exe, "topic", "echo", "/joint_states", "--once", "--domain-id", domain],
            cwd=work, env=env, capture_output=True, text=True, timeout=300,
        )  # fmt: skip
        if echo.returncode != 0 or "joint_1" not in echo.stdout:
            raise SmokeError(
                f"topic echo /joint_states over Zenoh failed:\n{echo.stdout}{echo.stderr}\n"
                f"launch log:\n{(work / 'launch.log').read_text()}"
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


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--python", nargs="+", type=Path, help="interpreters (default: found)")
    parser.add_argument(
        "--require-all", action="store_true", help="fail if a claimed Python is missing"
    )
    args = parser.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    if args.python:
        pythons = {_version(p) or str(p): p for p in args.python}
    else:
        pythons = find_pythons()
        missing = [m for m in CLAIMED if m not in pythons]
        if missing:
            print(f"wheel-smoke: no Python {', '.join(missing)} on this machine", file=sys.stderr)
            if args.require_all:
                return 1
    start = time.monotonic()
    wheel = build_wheel()
    print(f"wheel-smoke: built {wheel.name} in {time.monotonic() - start:.0f} s", flush=True)
    failed = []
    for minor, python in sorted(pythons.items()):
        try:
            seconds = smoke(minor, python, wheel)
        except (SmokeError, subprocess.TimeoutExpired) as exc:
            failed.append(minor)
            print(
                f"wheel-smoke: Python {minor} ({python}) FAILED: {exc}", file=sys.stderr, flush=True
            )
            continue
        print(f"wheel-smoke: Python {minor} ({python}): passed in {seconds:.0f} s", flush=True)
    print(f"wheel-smoke: {time.monotonic() - start:.0f} s in all", flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
