"""Shared fixtures: reference tools (urdfdom's check_urdf), corpora and a CLI runner."""

from __future__ import annotations

import contextlib
import itertools
import os
import shutil
import signal
import subprocess
import sys
import sysconfig
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from hypothesis import settings

from robomodel.cli.main import main
from tests.tiers import MARKERS, child_pids, in_process_only, tiers_of
from tests.timing import scaled, wait_until

# No per-example deadline: timing belongs in bench/, and a loaded CI machine must not fail tests.
settings.register_profile("robomodel", deadline=None)
settings.load_profile("robomodel")

ROOT = Path(__file__).resolve().parents[1]
ROBOMODEL = [sys.executable, "-m", "robomodel.cli.main"]  # the CLI in a process of its own
EXAMPLES = ROOT / "examples"


_DOMAINS = itertools.count()


_ROUTER: subprocess.Popen[bytes] | None = None
_ROUTER_LINK: Any = None  # a zenoh.Session, when the run found a router running
_TMPDIR: str | None = None  # the processes' TMPDIR, removed at the end of the run


def _processes_tmpdir() -> None:
    """Give every process the tests start a TMPDIR of this run's own, removed at its end.

    Debian's genpy (behind rostopic, rosbag, rosservice) writes each message type it builds
    to a ``genpy_*`` folder in TMPDIR and removes it at exit, which a tool ended by SIGTERM
    never reaches: a full run left dozens in /tmp. xdist's workers start after this and
    inherit it (the controlling process removes it once they are done)."""
    global _TMPDIR
    import tempfile

    _TMPDIR = tempfile.mkdtemp(prefix="robomodel-tests-")
    os.environ["TMPDIR"] = _TMPDIR
    # pytest's own folders (tmp_path, xdist's per-worker ones) too: its basetemp is made in
    # the temporary folder Python found first, which it keeps (tempfile.tempdir)
    tempfile.tempdir = _TMPDIR
    # The record and log of a router a robomodel process starts go to XDG_RUNTIME_DIR (else
    # /tmp/robomodel-UID): this run's, removed with it.
    runtime = Path(_TMPDIR) / "run"
    runtime.mkdir(mode=0o700)
    os.environ["XDG_RUNTIME_DIR"] = str(runtime)


def _byte_code_cache() -> None:
    """Let the run's processes keep byte code where the environment says to write none
    (``PYTHONDONTWRITEBYTECODE``, set to keep ``__pycache__`` folders out of the checkout): in
    ``build/pycache`` (``PYTHONPYCACHEPREFIX``), beside the run's screenshots. Without it every
    ``robomodel`` process a test starts compiles each module it imports from source again, a
    second or more for the viewer, launch or simulator, and each xdist worker rewrites every
    test module's asserts again. A ``PYTHONPYCACHEPREFIX`` of the user's own is kept. The xdist
    workers start after this and inherit it."""
    if not os.environ.get("PYTHONDONTWRITEBYTECODE") or os.environ.get("PYTHONPYCACHEPREFIX"):
        return
    cache = ROOT / "build" / "pycache"
    try:
        cache.mkdir(parents=True, exist_ok=True)
    except OSError:
        return  # a read-only checkout: every process compiles, as the environment asks
    del os.environ["PYTHONDONTWRITEBYTECODE"]
    os.environ["PYTHONPYCACHEPREFIX"] = str(cache)


def _listening(port: int) -> bool:
    import socket

    with socket.socket() as probe:
        probe.settimeout(0.2)
        return probe.connect_ex(("127.0.0.1", port)) == 0


def pytest_configure(config: pytest.Config) -> None:
    """One Zenoh router for the whole run, as a ROS 2 user runs ``rmw_zenohd``: started by
    the controlling process (not by an xdist worker), so that the robomodel processes of every
    test find the same router however short-lived the others are. Without it the first process
    of a test becomes the router and takes it along when it exits (tested on its own port in
    tests/runtime/test_zenoh_router.py)."""
    global _ROUTER
    for name, description in MARKERS.items():
        config.addinivalue_line("markers", f"{name}: {description}")
    # robomodel's verbs take the ROS 1 bus when ROS_MASTER_URI is set: tests that want it set
    # it for their own processes (tests/ros1wire)
    os.environ.pop("ROS_MASTER_URI", None)
    # A shell without job control starts background commands with SIGINT ignored (`make test &`
    # in a script, `nohup ... &`), and every process of the run would inherit that: Ctrl-C
    # tests then saw nothing, and a plain Python child ignored SIGINT. Each process of the
    # run (the controller and every xdist worker) takes Python's own handler, as from a
    # terminal; the tests of starting with SIGINT ignored set that up for their child.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    if hasattr(config, "workerinput"):
        return
    _processes_tmpdir()
    _byte_code_cache()
    if os.environ.get("ROBOMODEL_TEST_ROUTER") == "0":  # tools/mutate.py: in-process tests only
        return
    if _listening(7447):
        _keep_router_alive()
        return
    _ROUTER = subprocess.Popen(
        [*ROBOMODEL, "router"], stderr=subprocess.DEVNULL, start_new_session=True
    )
    # On a cold start (no byte code yet, a busy machine) the router takes seconds to listen:
    # a worker's session that found none would start a router of its own on 7447, which
    # stops once idle (in the middle of the run) and takes the port from this one.
    router = _ROUTER

    def listens() -> bool:
        if _listening(7447):
            return True
        if router.poll() is not None:
            raise pytest.UsageError(
                f"the run's Zenoh router ended (`robomodel router` exit code {router.poll()})"
            )
        return False

    try:
        wait_until(listens, 60, what="the run's Zenoh router on tcp/localhost:7447")
    except AssertionError as exc:
        raise pytest.UsageError(str(exc)) from None


# Tests run first: long ones that mostly wait on processes of their own, so that they run
# beside the rest of the suite (xdist hands out tests in this order) rather than after it.
STARTED_FIRST = ("tests/test_wheel_smoke.py",)


def pytest_itemcollected(item: pytest.Item) -> None:
    """Mark the test with the tiers it belongs to (tests/tiers.py): from the fixtures of its
    closure, and from PATH_TIERS for one that starts its processes itself. Marked as it is
    collected, so that ``-m`` (``make test-fast``) selects by these marks."""
    defs = getattr(item, "_fixtureinfo", None)
    fixtures = [
        (definitions[-1].baseid, name)
        for name, definitions in (defs.name2fixturedefs.items() if defs else ())
        if definitions
    ]
    for marker in sorted(tiers_of(item.nodeid, fixtures)):
        item.add_marker(marker)


@pytest.hookimpl(trylast=True)  # after xdist's own, which names the groups its way
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """The tests of :data:`STARTED_FIRST` go to the front and the in-process tier to the
    back: its many short tests fill the workers while the last long ones finish, instead of a
    long one starting last (xdist hands tests out in this order). Then
    :func:`_name_xdist_groups`."""
    items.sort(key=_start_order)
    _name_xdist_groups(config, items)


def _name_xdist_groups(config: pytest.Config, items: list[pytest.Item]) -> None:
    """In an xdist worker under ``--dist loadgroup``, end each grouped test's id with
    ``@GROUP``, which is what the controller groups by. pytest-xdist 3.8 does this by setting
    ``item._nodeid``, which pytest 9 no longer reads (an item's id is ``item._id``): its
    groups were silently spread over the workers, and a group's module-scoped fixture started
    once per worker and test."""
    from _pytest.nodeid import coerce_node_id

    if not (hasattr(config, "workerinput") and config.getvalue("loadgroup")):
        return
    for item in items:
        names = {str(m.args[0] if m.args else m.kwargs.get("name", "default"))
                 for m in item.iter_markers("xdist_group")}  # fmt: skip
        if names and "@" not in item.nodeid and hasattr(item, "_id"):
            item._id = coerce_node_id(f"{item.nodeid}@{'_'.join(sorted(names))}")


def _start_order(item: pytest.Item) -> int:
    if item.nodeid.startswith(STARTED_FIRST):
        return 0
    return 1 if any(item.get_closest_marker(name) for name in MARKERS) else 2


@pytest.fixture(autouse=True)
def _in_process_tier_stays_in_process(request: pytest.FixtureRequest) -> Iterator[None]:
    """A test with none of the tier markers (``make test-fast`` runs those) starts no process,
    opens no Zenoh session and binds no socket beyond loopback; one that does fails, naming the
    marker it lacks."""
    if any(request.node.get_closest_marker(name) for name in MARKERS):
        yield
        return
    with in_process_only(request.node.nodeid):
        yield


def pytest_report_header(config: pytest.Config) -> str:
    from tests.timing import scale, scale_source

    return f"robomodel test timeout scale: {scale():.2f} ({scale_source()})"


def _keep_router_alive() -> None:
    """A router already on 7447 may be one that ``robomodel`` started for an earlier command
    (``--idle-exit 60``): it would stop once no session is linked, possibly in the middle of a
    test whose processes then meet on a new router while the test's own session stays with the
    old one. A session of the run's own, linked for the whole run, keeps it up."""
    global _ROUTER_LINK
    from robomodel.runtime.transport._zenoh_session import open_session

    # a session as robomodel's processes open one: a peer, which the router counts
    _ROUTER_LINK = open_session().session


def pytest_unconfigure(config: pytest.Config) -> None:
    if _ROUTER_LINK is not None:
        _ROUTER_LINK.close()
    if _ROUTER is not None:
        _ROUTER.terminate()
        try:
            _ROUTER.wait(scaled(10))
        except subprocess.TimeoutExpired:
            _ROUTER.kill()
            _ROUTER.wait()
    if _TMPDIR is not None:
        shutil.rmtree(_TMPDIR, ignore_errors=True)


def unique_domain() -> str:
    """A Zenoh domain id (1..230) no other test running at the same time uses.

    Tests that start processes on the Zenoh bus must not hear each other: a /gazebo/pause or a
    cmd_vel from a test on the other xdist worker would reach this test's simulator. Each worker
    gets its own block of ids and walks through it, so consecutive tests of one worker differ too.
    ``ROBOMODEL_TEST_DOMAIN_BASE`` (0..229, default 0) and ``ROBOMODEL_TEST_DOMAIN_COUNT``
    (default: the rest up to 230) give a run its own block of ids, so that runs on one machine
    do not hear each other: e.g. ``ROBOMODEL_TEST_DOMAIN_COUNT=115`` for one and
    ``ROBOMODEL_TEST_DOMAIN_BASE=115`` for the other.
    """
    base, count = _domain_block()
    workers = max(1, int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1")))
    worker = int(os.environ.get("PYTEST_XDIST_WORKER", "gw0").removeprefix("gw") or 0)
    span = max(1, count // workers)
    return str(1 + base + (worker * span + next(_DOMAINS) % span) % count)


def _domain_block() -> tuple[int, int]:
    """(base, count) of this run's domain ids, from the environment."""
    base_text = os.environ.get("ROBOMODEL_TEST_DOMAIN_BASE", "").strip() or "0"
    if not base_text.isdigit() or int(base_text) > 229:
        raise ValueError(f"ROBOMODEL_TEST_DOMAIN_BASE must be an integer 0..229, got '{base_text}'")
    base = int(base_text)
    count_text = os.environ.get("ROBOMODEL_TEST_DOMAIN_COUNT", "").strip() or str(230 - base)
    if not count_text.isdigit() or not 1 <= int(count_text) <= 230 - base:
        raise ValueError(
            f"ROBOMODEL_TEST_DOMAIN_COUNT must be an integer 1..{230 - base}, got '{count_text}'"
        )
    return base, int(count_text)


_PORTS = itertools.count()
_PORT_LOW, _PORT_LANES, _PORTS_PER_LANE = 12000, 256, 80  # 12000..32479: below Linux's 32768


def free_port() -> int:
    """A free TCP port on 127.0.0.1 for a server a test starts itself (a roscore, a master,
    a router), that no other process is handed meanwhile.

    A port from ``bind(0)`` comes from the kernel's ephemeral range (32768-60999), which every
    client socket and every node's XML-RPC server draws from too: between the probe and the
    server's own bind, a ROS node of the other xdist worker took one (seen under load: the
    test's launch found a node where its master should start, "setParam is not supported").
    These ports lie below that range, in a lane per xdist worker and per domain block (so two
    runs with different ``ROBOMODEL_TEST_DOMAIN_BASE`` differ too), and are checked free."""
    import socket

    base, _count = _domain_block()
    worker = int(os.environ.get("PYTEST_XDIST_WORKER", "gw0").removeprefix("gw") or 0)
    lane = (base + worker) % _PORT_LANES
    for _ in range(_PORTS_PER_LANE):
        port = _PORT_LOW + lane * _PORTS_PER_LANE + next(_PORTS) % _PORTS_PER_LANE
        with socket.socket() as probe:
            try:
                probe.bind(("127.0.0.1", port))
            except OSError:
                continue  # in use (or lingering): the next one
            return port
    raise RuntimeError(f"no free port in lane {lane} ({_PORTS_PER_LANE} tried)")


def past_the_bus_line(stream: Any) -> str:
    """The first line a long-running verb writes after the line naming the graph it joined
    (``robomodel sim: bus: zenoh ...``), which every such verb prints first."""
    line = stream.readline()
    if ": bus: " in line:
        line = stream.readline()
    return str(line)


def importorskip_mujoco() -> Any:
    """``mujoco``, imported as robomodel imports it (without GLFW's version probe, which
    starts a Python process: an in-process test may not), or the test skipped without it."""
    from robomodel._mujoco_import import import_mujoco

    try:
        return import_mujoco()
    except ImportError:
        pytest.skip("mujoco is not installed (the sim extra)")


def example_robot_data_dir() -> Path:
    """The robots of the example-robot-data wheel (installed by the test extra)."""
    prefix = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix"
    return prefix / "share" / "example-robot-data" / "robots"


def example_robot_data_urdfs() -> list[Path]:
    return sorted(example_robot_data_dir().rglob("*.urdf"))


def example_urdfs() -> list[Path]:
    return sorted(EXAMPLES.rglob("*.urdf"))


@dataclass(frozen=True)
class ToolResult:
    code: int
    out: str
    err: str


def _run(cmd: list[str], env: dict[str, str] | None = None, timeout: float = 60) -> ToolResult:
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=timeout)
    return ToolResult(proc.returncode, proc.stdout, proc.stderr)


def debian_check_urdf() -> str:
    """Debian's check_urdf (urdfdom 3.0.1, package liburdfdom-tools); required in CI."""
    path = shutil.which("check_urdf")
    if path is None:
        pytest.fail("check_urdf is not installed: apt-get install liburdfdom-tools (.ci/run does)")
    return path


def urdfdom6_check_urdf() -> tuple[str, dict[str, str]]:
    """urdfdom 6.0's check_urdf, shipped inside the pin wheel (URDF 1.1 and 1.2 support)."""
    prefix = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix"
    exe = prefix / "bin" / "check_urdf"
    if not exe.exists():
        pytest.fail("urdfdom 6 check_urdf missing from the pin wheel (test extra)")
    env = dict(os.environ, LD_LIBRARY_PATH=str(prefix / "lib"))
    return str(exe), env


@pytest.fixture
def check_urdf() -> Callable[..., ToolResult]:
    """Run a reference check_urdf: Debian's for URDF 1.0, urdfdom 6 for versions 1.1/1.2."""

    def run(
        path: Path | str, *, urdfdom6: bool = False, timeout: float | None = None
    ) -> ToolResult:
        timeout = scaled(60) if timeout is None else timeout
        if urdfdom6:
            exe, env = urdfdom6_check_urdf()
            return _run([exe, str(path)], env=env, timeout=timeout)
        return _run([debian_check_urdf(), str(path)], timeout=timeout)

    return run


@pytest.fixture
def cli(capsys: pytest.CaptureFixture[str]) -> Callable[..., ToolResult]:
    """Run the robomodel CLI in-process and capture its exit code and output."""

    def run(*args: str) -> ToolResult:
        code = main(list(args))
        captured = capsys.readouterr()
        return ToolResult(code, captured.out, captured.err)

    return run


def end_process(
    proc: subprocess.Popen[Any],
    sig: int = signal.SIGINT,
    *,
    timeout_s: float = 10.0,
    group: bool = False,
) -> int:
    """End a process a test started: ``sig`` (to its process group with ``group``), a scaled
    ``timeout_s`` to exit, then SIGKILL. Returns its exit code (negative: killed by a signal).
    Nothing is done to one that has exited already."""
    if proc.poll() is None:
        send = (lambda s: os.killpg(proc.pid, s)) if group else proc.send_signal
        with contextlib.suppress(ProcessLookupError):
            send(sig)
        try:
            proc.wait(scaled(timeout_s))
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                send(signal.SIGKILL)
            proc.wait()
    return int(proc.returncode)


def _children() -> dict[int, str]:
    """The live (not zombie) child processes of this process: pid -> command line."""
    found: dict[int, str] = {}
    for pid in child_pids():
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as cmdline:
                found[pid] = cmdline.read().replace(b"\0", b" ").decode().strip()
        except OSError:
            continue
    return found


_SIGNALS = (signal.SIGINT, signal.SIGTERM)


def _kernel_ignore_mask() -> int:
    """The signals ignored at the OS level (what a child process inherits), whatever Python's
    own table says: bit ``signum - 1`` of /proc's SigIgn."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("SigIgn:"):
                return int(line.split()[1], 16)
    return 0


@pytest.fixture(autouse=True)
def _signal_handlers_put_back(request: pytest.FixtureRequest) -> Iterator[None]:
    """Each test starts with the worker's SIGINT and SIGTERM handlers, whatever the tests before
    it changed: ``robomodel.cli.main`` run in-process installs its own on purpose, and a test
    that checks Ctrl-C (or a child that inherits SIGINT's disposition) must not depend on which
    tests the worker ran first. A change other than the command line's is reported."""
    from robomodel.cli import main as cli_main

    saved = {signum: signal.getsignal(signum) for signum in _SIGNALS}
    ignored = _kernel_ignore_mask()
    yield
    ours = (cli_main._raise_interrupt, cli_main._raise_terminated)
    flipped = _kernel_ignore_mask() ^ ignored
    changed = [
        signum.name
        for signum in _SIGNALS
        if (signal.getsignal(signum) is not saved[signum] and signal.getsignal(signum) not in ours)
        or flipped >> (signum - 1) & 1
    ]
    for signum, handler in saved.items():
        if handler is not None:
            signal.signal(signum, handler)
    if changed:
        import warnings

        warnings.warn(
            f"{request.node.nodeid} left {', '.join(changed)} changed (put back)", stacklevel=1
        )


# What a test starts and must end itself. Not the browser of the session-scoped playwright
# fixture, which lives across tests on purpose.
_OURS = ("robomodel", "rosmaster", "roscore", "roslaunch", "rostopic", "rosbag", "rviz", "Xvfb",
         "robot_state_publisher")  # fmt: skip


def _end(pid: int) -> None:
    with contextlib.suppress(OSError):
        os.killpg(pid, signal.SIGKILL)  # a leader of its own group: everything it started
    with contextlib.suppress(OSError):
        os.kill(pid, signal.SIGKILL)
    with contextlib.suppress(OSError):
        os.waitpid(pid, 0)


@pytest.fixture(autouse=True)
def _no_process_left_behind() -> Iterator[None]:
    """A test that fails half-way must not leave its robomodel processes running for good (a
    ``robomodel topic echo`` did): what a test started and did not end is ended here, with its
    process group, and reported as a warning."""
    before = set(_children())
    yield
    left = {p: c for p, c in _children().items() if p not in before and any(o in c for o in _OURS)}
    deadline = time.monotonic() + scaled(2.0)
    while left and time.monotonic() < deadline:  # some are just exiting
        time.sleep(0.05)
        left = {pid: cmd for pid, cmd in _children().items() if pid in left}
    for pid in left:
        _end(pid)
    if left:
        import warnings

        warnings.warn(f"the test left processes running (now killed): {left}", stacklevel=1)


@pytest.fixture(autouse=True)
def _temporary_files_in_pytest_s_basetemp(
    tmp_path_factory: pytest.TempPathFactory, monkeypatch: pytest.MonkeyPatch
) -> None:
    """What code run in the test process writes with ``tempfile`` (the ``launch_params_*.yaml``
    files the ROS 2 ``load_launch`` API leaves for the caller's nodes) goes to a folder of
    pytest's basetemp, inside the run's temporary folder that is removed at its end, not to
    /tmp."""
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path_factory.mktemp("tempfile")))
