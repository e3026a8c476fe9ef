"""The seeds as a student types them.

Each module builds one seed's packages from the seed's own file text in a temporary workspace
and runs the seed's command lines in order: ROS 1 seeds with Debian's real ``rostopic``,
``rosparam``, ``rosnode`` and ``rosservice`` against the master a ``robomodel launch`` hosts (and
beside a real ``roscore`` where that is practical), ROS 2 seeds with robomodel's CLI on the
Zenoh bus. The ROS tools robomodel replaces are typed as robomodel's equivalents
(``roslaunch``/``ros2 launch`` → ``robomodel launch``, ``check_urdf`` → ``robomodel check``,
``xacro`` → ``robomodel xacro``, ``ros2 control`` → ``robomodel control``, ``ros2 topic`` →
``robomodel topic``).

Every wait is for a condition, bounded by :data:`TIMEOUT_S`, the one place that says how long a
step may take, times the machine's factor (:func:`tests.timing.scaled`) on a loaded one.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import subprocess
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.conftest import ROBOMODEL, unique_domain
from tests.ros1wire.conftest import ROSCORE, Ros1
from tests.timing import scaled, wait_until

TIMEOUT_S = 90.0
"""The longest any step may take to show what it should (a launch to start, a joint to arrive)."""

LINE_TIMEOUT_S = 30.0
"""The longest a launch that runs may take to show what comes with its start (a hint line, a
node's topic once another node of it is seen): shorter, so that a test marked xfail for a
missing line or topic ends soon."""

_ATTEMPT_S = 10.0  # one try of a command that waits for a peer (rostopic echo)

ROSTOPIC, ROSPARAM, ROSNODE, ROSSERVICE = (
    f"/usr/bin/{tool}" for tool in ("rostopic", "rosparam", "rosnode", "rosservice")
)


def write_tree(root: Path, files: Mapping[str, str | bytes]) -> Path:
    """Write ``relative path -> text`` under ``root`` (the student's editor)."""
    for relative, content in files.items():
        path = root / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(content)
    return root


def package_xml(name: str) -> str:
    """What ``catkin_create_pkg NAME`` / ``ros2 pkg create NAME`` writes, reduced to the name."""
    return (
        f'<?xml version="1.0"?>\n<package format="2">\n  <name>{name}</name>\n'
        "  <version>0.0.0</version>\n  <description>seed package</description>\n"
        "  <maintainer email='student@example.com'>student</maintainer>\n"
        "  <license>BSD</license>\n</package>\n"
    )


def box_stl(size_xyz_m: tuple[float, float, float]) -> bytes:
    """An ASCII STL box centred on the origin: the "provided mesh files" seed 000 copies."""
    hx, hy, hz = (s / 2 for s in size_xyz_m)
    corners = [(x, y, z) for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    lines = ["solid box"]
    for a, b, c, d in faces:
        for tri in ((a, b, c), (a, c, d)):
            lines += ["facet normal 0 0 0", "outer loop"]
            lines += [f"vertex {x} {y} {z}" for x, y, z in (corners[i] for i in tri)]
            lines += ["endloop", "endfacet"]
    lines.append("endsolid box")
    return ("\n".join(lines) + "\n").encode()


def until(
    check: Callable[[], Any], what: str, timeout_s: float = TIMEOUT_S, *, log: Path | None = None
) -> Any:
    """``wait_until`` at the pace of a CLI call: fails naming ``what`` (and showing the end of
    ``log``) after ``timeout_s`` (scaled with the machine)."""

    def described() -> str:
        return what if log is None else f"{what}\n{log.name}:\n{log.read_text()[-4000:]}"

    return wait_until(check, timeout_s, what=described, interval_s=0.3)


@dataclass
class SeedRos1(Ros1):
    """A ROS 1 graph whose package path is the seed's workspace (``source devel/setup.bash``)."""

    packages: str = ""

    @property
    def env(self) -> dict[str, str]:
        return {**super().env, "ROS_PACKAGE_PATH": self.packages}

    def launch(self, log: Path, *argv: str, wait_for: str) -> subprocess.Popen[str]:
        """``roslaunch PKG FILE`` as ``robomodel launch``, running once ``wait_for`` is logged."""
        proc = self.robomodel("launch", *argv, "--headless", log=log)
        until(
            lambda: wait_for in log.read_text() or proc.poll() is not None,
            f"'{wait_for}' in {log.name}",
            log=log,
        )
        assert proc.poll() is None, log.read_text()
        return proc

    def tool(self, *argv: str, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
        """A Debian ROS 1 tool (or any command) on this graph."""
        return subprocess.run(
            list(argv), capture_output=True, text=True, env=self.env, cwd=cwd,
            timeout=scaled(TIMEOUT_S),
        )  # fmt: skip

    def echo(self, topic: str) -> Any:
        """The first message of ``rostopic echo -n 1 TOPIC``, as YAML; fails at once when a
        process this graph started has ended (a launch that shut down publishes nothing)."""

        def once() -> Any:
            ended = [p.args for p in self.procs if p.poll() is not None]
            assert not ended, f"ended before {topic} had a message: {ended}"
            try:  # rostopic echo waits for a publisher for good: ask again in a while
                out = subprocess.run(
                    [ROSTOPIC, "echo", "-n", "1", topic],
                    capture_output=True, text=True, env=self.env, timeout=scaled(_ATTEMPT_S),
                )  # fmt: skip
            except subprocess.TimeoutExpired:
                return None
            return yaml.safe_load(out.stdout.split("\n---")[0]) if out.returncode == 0 else None

        return until(once, f"rostopic echo {topic}")


MASTERS = ["robomodel-master", "roscore"]


def grouped_by_master(group: str, *, only: str | None = None) -> list[Any]:
    """:data:`MASTERS` (or ``only`` of them) as the params of a module-scoped graph fixture,
    each marked with an xdist group of its own (``GROUP-MASTER``): the tests of one started
    graph go to one worker, which starts it once; the two graphs may still run on two workers."""
    return [
        pytest.param(m, id=m, marks=pytest.mark.xdist_group(f"{group}-{m}"))
        for m in MASTERS
        if only in (None, m)
    ]


@pytest.fixture
def ros1_graph(tmp_path: Path) -> Iterator[SeedRos1]:
    """A ROS 1 graph for a seed test, its workspace at ``tmp_path/catkin_ws/src``."""
    for tool in (ROSCORE, ROSTOPIC, ROSPARAM, ROSNODE, ROSSERVICE):
        if not Path(tool).exists():
            pytest.fail(f"Debian's ROS 1 is missing ({tool}): tools/system-deps test installs it")
    workspace = tmp_path / "catkin_ws" / "src"
    workspace.mkdir(parents=True)
    graph = SeedRos1(tmp_path, packages=str(workspace))
    try:
        yield graph
    finally:
        graph.close()


def start_master(graph: SeedRos1, which: str) -> None:
    """``roscore`` first, or nothing: then the first ``robomodel launch`` hosts the master."""
    if which == "roscore":
        graph.roscore()


@dataclass
class Ros2Workspace:
    """A colcon workspace (``~/ros2_ws``): packages under ``src``, ``colcon build`` copying
    their installed folders to ``install/<pkg>/share/<pkg>``, commands run from its root after
    ``. install/setup.bash`` (``AMENT_PREFIX_PATH``), on a Zenoh domain of their own."""

    root: Path
    domain: str = field(default_factory=unique_domain)  # keeps xdist workers apart
    prefixes: list[Path] = field(default_factory=list)
    procs: list[subprocess.Popen[str]] = field(default_factory=list)

    @property
    def src(self) -> Path:
        return self.root / "src"

    def colcon_build(self, package: str, installed: tuple[str, ...]) -> Path:
        """``install(DIRECTORY <installed...> DESTINATION share/${PROJECT_NAME})`` + package.xml."""
        prefix = self.root / "install" / package
        share = prefix / "share" / package
        if share.exists():
            shutil.rmtree(share)
        share.mkdir(parents=True)
        shutil.copy(self.src / package / "package.xml", share / "package.xml")
        for folder in installed:
            if (self.src / package / folder).is_dir():
                shutil.copytree(self.src / package / folder, share / folder)
        marker = prefix / "share" / "ament_index" / "resource_index" / "packages" / package
        marker.parent.mkdir(parents=True, exist_ok=True)
        marker.write_text("")
        if prefix not in self.prefixes:
            self.prefixes.append(prefix)
        return share

    @property
    def env(self) -> dict[str, str]:
        return {
            **{k: v for k, v in os.environ.items() if not k.startswith(("ROS", "AMENT"))},
            "AMENT_PREFIX_PATH": os.pathsep.join(str(p) for p in self.prefixes),
            "PYTHONUNBUFFERED": "1",
        }

    def robomodel(self, *argv: str, timeout: float = TIMEOUT_S) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [*ROBOMODEL, *argv, "--domain-id", self.domain],
            capture_output=True, text=True, env=self.env, cwd=self.root, timeout=scaled(timeout),
        )  # fmt: skip

    def robomodel_plain(self, *argv: str) -> subprocess.CompletedProcess[str]:
        """A verb that takes no bus options (``check``, ``xacro``), from the workspace's root."""
        return subprocess.run(
            [*ROBOMODEL, *argv],
            capture_output=True, text=True, env=self.env, cwd=self.root,
            timeout=scaled(TIMEOUT_S),
        )  # fmt: skip

    def start(self, log: Path, *argv: str) -> subprocess.Popen[str]:
        with log.open("w") as out:
            proc = subprocess.Popen(
                [*ROBOMODEL, *argv, "--domain-id", self.domain],
                stdout=out, stderr=subprocess.STDOUT, text=True, env=self.env, cwd=self.root,
                start_new_session=True,
            )  # fmt: skip
        self.procs.append(proc)
        return proc

    def launch(self, log: Path, *argv: str, wait_for: str) -> subprocess.Popen[str]:
        proc = self.start(log, "launch", *argv, "--headless")
        until(
            lambda: wait_for in log.read_text() or proc.poll() is not None,
            f"'{wait_for}' in {log.name}",
            log=log,
        )
        assert proc.poll() is None, log.read_text()
        return proc

    def wait_for_topics(self, *topics: str, timeout_s: float = TIMEOUT_S) -> set[str]:
        """``robomodel topic list`` until it lists ``topics``; returns the list."""

        def listed() -> set[str] | None:
            names = set(self.robomodel("topic", "list").stdout.split())
            return names if set(topics) <= names else None

        found: set[str] = until(listed, f"{', '.join(topics)} listed", timeout_s)
        return found

    def echo(self, topic: str, *, timeout_s: float = TIMEOUT_S) -> Any:
        """The first message of ``robomodel topic echo TOPIC --once``, as YAML; fails at once
        when a process this workspace started has ended."""

        def once() -> Any:
            ended = [p.args for p in self.procs if p.poll() is not None]
            assert not ended, f"ended before {topic} had a message: {ended}"
            attempt_s = f"{scaled(_ATTEMPT_S):.1f}"
            out = self.robomodel("topic", "echo", topic, "--once", "--timeout", attempt_s)
            return yaml.safe_load(out.stdout.split("---")[0]) if out.returncode == 0 else None

        return until(once, f"robomodel topic echo {topic}", timeout_s)

    def close(self) -> None:
        for proc in reversed(self.procs):
            if proc.poll() is None:
                with contextlib.suppress(OSError):
                    os.killpg(proc.pid, 2)
                try:
                    proc.wait(scaled(20))
                except subprocess.TimeoutExpired:
                    os.killpg(proc.pid, 9)
                    proc.wait()


@pytest.fixture
def ros2_ws(tmp_path: Path) -> Iterator[Ros2Workspace]:
    pytest.importorskip("zenoh")
    workspace = Ros2Workspace(tmp_path / "ros2_ws")
    workspace.src.mkdir(parents=True)
    try:
        yield workspace
    finally:
        workspace.close()


def joint_position(message: Any, joint: str) -> float:
    """The position of ``joint`` in a sensor_msgs/JointState as YAML."""
    return float(message["position"][message["name"].index(joint)])
