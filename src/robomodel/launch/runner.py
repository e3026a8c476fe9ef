"""Run a launch file's nodes in this process, as ``roslaunch`` runs them as processes.

Order (roslaunch's): parameters are cleared (``clear_params``, ``<rosparam command="delete">``),
set on the domain's parameter server (hosted here if no other robomodel process hosts it),
dumped (``command="dump"``), then the nodes start in file order. A node robomodel provides runs
in-process (``robomodel.launch.nodes``); a node of the user's own package (an rclpy or rospy
program) runs as a child process (``robomodel.launch.user_nodes``), found as ``ros2 run`` and
``rosrun`` find it (``robomodel.launch.executables``). A node that is neither (an unknown
package, a C++ node) is reported once and the others go on; ``required="true"`` on such a node
is an error before anything starts. A required node that ends ends the launch; ``respawn`` restarts
a node after ``respawn_delay``. Ctrl-C stops every node in reverse start order.
"""

from __future__ import annotations

import signal
import sys
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from robomodel._watchdog import ends_process_after
from robomodel.description.packages import PackageIndex
from robomodel.errors import RobomodelError
from robomodel.launch.gui import GuiOptions, LaunchGui
from robomodel.launch.model import LaunchError, NodeSpec
from robomodel.launch.nodes.base import (
    LaunchShared,
    NodeContext,
    RunningNode,
    ViewerRequest,
    factory_for,
    supported,
)

__all__ = ["LaunchRunner", "RunOptions", "unsupported_message"]


@dataclass(frozen=True, slots=True)
class RunOptions:
    """How to run: the bus, the viewer, and (for scripts and tests) how long."""

    bus: str = "zenoh"
    domain_id: int | None = None
    headless: bool = False
    open_browser: bool = True
    port: int = 8080
    duration_s: float | None = None
    package_index: Any = None
    master_uri: str | None = None  # the ROS 1 master (bus "ros1"); default ROS_MASTER_URI
    strict_start: bool = False  # a node whose start fails raises (robomodel run), not logged
    connect: tuple[str, ...] = ()  # Zenoh endpoints to connect to / listen on (robomodel run)
    listen: tuple[str, ...] = ()
    launch_file: str | None = None  # the file run (nodes name it in hints)


def unsupported_message(spec: NodeSpec) -> str:
    """One clear line for a node robomodel does not provide."""
    same_package = [e for p, e, _ in supported(spec.dialect) if p == spec.package]
    hint = (
        f"; robomodel provides {spec.package}'s {', '.join(same_package)}" if same_package else ""
    )
    return (
        f"{spec.location}: node {spec.fqn} ({spec.package}/{spec.executable}) is not started: "
        f"robomodel maps no such node{hint} and no package '{spec.package}' is on the package "
        "path (add the workspace that holds it with --package-path DIR or ROS_PACKAGE_PATH; "
        "see `robomodel launch --help` for the nodes robomodel maps)"
    )


@dataclass
class _Started:
    spec: NodeSpec
    handle: RunningNode
    restarts: int = 0
    ended_at: float | None = None


@dataclass
class LaunchRunner:
    """Runs the nodes of a loaded launch (see the module docstring)."""

    nodes: Sequence[NodeSpec]
    options: RunOptions
    steps: Sequence[Any] = ()  # ROS 2: LaunchStep values (then ``nodes`` are their nodes)
    log: Callable[[str], None] = field(default=lambda text: _write_line(text))
    params: Any = None
    context: Any = None
    started: list[_Started] = field(default_factory=list)
    skipped: list[NodeSpec] = field(default_factory=list)
    request: ViewerRequest = field(default_factory=ViewerRequest)
    hosted_params: bool = False
    _stop: threading.Event = field(default_factory=threading.Event)
    _terminated: bool = False
    _scheduler: Any = None
    _ros1: Any = None
    _node_log: Any = None  # NodeLogToLaunch, while the bus is open
    _processes: int = 0  # the user's node processes started (ros2 launch numbers them)
    shared: LaunchShared | None = None  # what the nodes share, once they start
    gui: LaunchGui | None = None  # made with ``shared``, started after the nodes

    # -- set-up ---------------------------------------------------------------------------
    def check(self) -> None:
        """Refuse, before anything starts, a required node robomodel cannot run."""
        for spec in self.nodes:
            if spec.required and self._factory(spec, report=False) is None:
                raise LaunchError(
                    f"required node {spec.fqn} ({spec.package}/{spec.executable}) can not be run "
                    f"by robomodel ({self._why_not(spec)}), so the launch cannot run (roslaunch "
                    'would end when it ends); remove required="true" to run the rest',
                    location=spec.location,
                )

    def _index(self) -> PackageIndex:
        if self.options.package_index is None:
            self.options = replace(self.options, package_index=PackageIndex())
        index: PackageIndex = self.options.package_index
        return index

    def _why_not(self, spec: NodeSpec) -> str:
        """Why ``spec`` has neither a mapping nor a user executable (one clause)."""
        from robomodel.launch.executables import find_executable

        try:
            package = self._index().get(spec.package)
            find_executable(spec.package, spec.executable, package.path)
        except RobomodelError as exc:
            return str(exc)
        return "it can be run"

    def user_executable(self, spec: NodeSpec) -> Any:
        """The user's executable for ``spec`` (a :class:`UserExecutable`), or None."""
        from robomodel.errors import PackageNotFoundError
        from robomodel.launch.executables import find_executable

        try:
            package = self._index().get(spec.package)
            return find_executable(spec.package, spec.executable, package.path)
        except PackageNotFoundError:
            return None
        except RobomodelError:
            return None

    def user_nodes(self) -> list[NodeSpec]:
        """The nodes that run as the user's own programs (no mapping, an executable found)."""
        return [s for s in self.nodes if factory_for(s) is None and self.user_executable(s)]

    def _factory(self, spec: NodeSpec, *, report: bool = True) -> Any:
        """How ``spec`` starts: robomodel's mapping first (its names keep priority), else the
        user's executable of that package as a child process; None (reported) if neither."""
        factory = factory_for(spec)
        if factory is not None:
            return factory
        found = self.user_executable(spec)
        if found is None:
            if report:
                self.skipped.append(spec)
                self.log(self._unrunnable_message(spec))
            return None

        def start_process(ctx: NodeContext) -> RunningNode:
            from robomodel.launch.user_nodes import UserNodeProcess

            self._processes += 1
            try:
                return UserNodeProcess(
                    spec,
                    found,
                    self.log,
                    master_uri=self._ros1.uri if self._ros1 is not None else None,
                    domain_id=self.options.domain_id,
                    number=self._processes,
                )
            except OSError as exc:
                raise RobomodelError(f"{' '.join(found.command())}: {exc}") from None

        return start_process

    def _unrunnable_message(self, spec: NodeSpec) -> str:
        from robomodel.errors import PackageNotFoundError

        try:
            self._index().get(spec.package)
        except PackageNotFoundError:
            return unsupported_message(spec)
        where = f"{spec.location}: " if spec.location is not None else ""
        return f"{where}node {spec.fqn} is not started: {self._why_not(spec)}"

    def open_bus(self) -> None:
        from robomodel.launch.node_log import NodeLogToLaunch
        from robomodel.launch.param_server import connect_or_host
        from robomodel.runtime import Context

        self._node_log = NodeLogToLaunch(self.log)
        self._node_log.attach()

        if self.options.bus == "ros1":
            from robomodel.launch.ros1_master import open_ros1

            ros1 = open_ros1(self.options.master_uri, self.log)
            self.context, self.params, self._ros1 = ros1.context, ros1.params, ros1
            self.hosted_params = ros1.master is not None
            return
        kwargs: dict[str, Any] = {}
        if self.options.bus == "zenoh" and self.options.domain_id is not None:
            kwargs["domain_id"] = self.options.domain_id
        if self.options.bus == "zenoh" and (self.options.connect or self.options.listen):
            kwargs.update(connect=list(self.options.connect), listen=list(self.options.listen))
        self.context = Context(self.options.bus, **kwargs)
        self.params, self.hosted_params = connect_or_host(self.context)
        where = "hosted by this process" if self.hosted_params else "of another robomodel process"
        self.log(f"[launch] parameter server {where}")
        self.log(f"[launch] {self.context.transport.describe()}")

    def set_params(
        self,
        params: dict[str, Any],
        *,
        clear: Sequence[str] = (),
        deletes: Sequence[str] = (),
        dumps: Sequence[Any] = (),
    ) -> None:
        """roslaunch's order: clear, delete, set, dump."""
        for name in (*clear, *deletes):
            if self.params.has(name):
                self.params.delete(name)
        for name, value in params.items():
            self.params.set(name, value)
        for dump in dumps:
            self._dump(dump.file, dump.param)

    def _dump(self, file: str, param: str) -> None:
        import yaml

        from robomodel._atomic import atomic_write_text

        value = self.params.get(param) if self.params.has(param) else {}
        atomic_write_text(file, yaml.safe_dump(value))

    # -- running --------------------------------------------------------------------------
    def start_nodes(self) -> None:
        options = self.options
        self.shared = LaunchShared(
            package_index=options.package_index or PackageIndex(),
            nodes=tuple(self.nodes),
            launch_file=options.launch_file,
        )
        gui_options = GuiOptions(
            headless=options.headless,
            open_browser=options.open_browser,
            port=options.port,
            bus=options.bus,
            domain_id=options.domain_id,
        )
        self.gui = LaunchGui(
            gui_options,
            self.request,
            self.shared,
            context=self.context,
            params=self.params,
            log=self.log,
        )
        if self.steps:
            from robomodel.launch.steps import StepScheduler

            self._scheduler = StepScheduler(self.steps, self._start_step)
            self._scheduler.begin()
            self.gui.start()
            return
        for spec in self.nodes:
            factory = self._factory(spec)
            if factory is not None:
                self._start(spec, factory=factory)
        self.gui.start()

    def _start_step(self, index: int, step: Any) -> Any:
        """Start one ROS 2 launch step; its handle (for OnProcessExit / OnProcessStart)."""
        from robomodel.launch.steps import ProcessNode, node_of_command

        if step.kind == "log":
            self.log(f"[INFO] [launch.user]: {step.message}")
            return _Done()
        if step.kind == "shutdown":
            self.log(f"[launch] shutdown requested: {step.message or 'Shutdown'}")
            self._stop.set()
            return _Done()
        spec = step.node if step.kind == "node" else node_of_command(step.command)
        if spec is None:
            name = " ".join(step.command[:1]) or "process"
            self.log(f"[launch] running {' '.join(step.command)}")
            try:
                handle: Any = ProcessNode(step.command, lambda text: self.log(f"[{name}] {text}"))
            except OSError as exc:
                self.log(f"[{name}] failed to start: {exc}")
                return _Failed()
            self.started.append(_Started(_process_spec(step), handle))
            return handle
        factory = self._factory(spec)
        if factory is None:
            return _Failed()
        self._start(spec, factory=factory)
        return self.started[-1].handle

    def _start(self, spec: NodeSpec, restarts: int = 0, *, factory: Any = None) -> None:
        factory = factory or self._factory(spec)
        assert factory is not None and self.shared is not None  # start_nodes made it
        ctx = NodeContext(
            spec, self.context, self.params, self.request, self._prefixed(spec), self.shared
        )
        try:
            handle = factory(ctx)
        except (RobomodelError, ValueError) as exc:
            if self.options.strict_start:
                raise
            self.log(f"[{spec.fqn}] failed to start: {exc}")
            handle = _Failed()
        self.started.append(_Started(spec, handle, restarts))
        self.log(f"[launch] started {spec.fqn} ({spec.package}/{spec.executable})")

    def _prefixed(self, spec: NodeSpec) -> Callable[[str], None]:
        from robomodel.runtime.rosout import publish_line

        def log(text: str) -> None:
            self.log(f"[{spec.fqn}] {text}")
            publish_line(self.context, spec.fqn, text)  # the node's /rosout, as its process

        return log

    def spin(self, stopped: Callable[[], bool] = lambda: False) -> int:
        """Run until Ctrl-C, ``duration_s``, a required node ending or ``stopped()`` (a signal
        the caller caught while the nodes started); the exit code."""
        deadline = (
            time.monotonic() + self.options.duration_s
            if self.options.duration_s is not None
            else None
        )
        previous: dict[signal.Signals, Any] = {}
        try:
            # A plain flag: Event.set takes a lock, and a second SIGTERM arriving inside it
            # (timeout, then pkill) would wait for that lock forever. Ctrl-C sets it too: a
            # KeyboardInterrupt raised inside a Zenoh callback (run on this thread for a local
            # sample) was swallowed by zenoh-python, and the launch did not end.
            for signum in (signal.SIGINT, signal.SIGTERM):
                previous[signum] = signal.signal(
                    signum, lambda *_: setattr(self, "_terminated", True)
                )
        except ValueError:  # not the main thread
            pass
        code = 0
        try:
            while not (self._stop.is_set() or self._terminated or stopped()):
                if deadline is not None and time.monotonic() >= deadline:
                    break
                driver = self._driver()
                if driver is not None:  # a simulator: physics, controllers and callbacks
                    driver.drive(0.05)
                else:
                    self.context.spin(duration_s=0.05)
                if self._scheduler is not None:
                    self._scheduler.poll()
                ended = self._supervise()
                if ended is not None:
                    code = ended
                    break
        except KeyboardInterrupt:
            code = 0
        finally:
            for signum, handler in previous.items():
                signal.signal(signum, handler)
        return code

    def _driver(self) -> Any:
        for entry in self.started:
            if hasattr(entry.handle, "drive") and entry.handle.exit_code() is None:
                return entry.handle
        return None

    def _supervise(self) -> int | None:
        now = time.monotonic()
        for entry in list(self.started):
            code = entry.handle.exit_code()
            if code is None:
                continue
            if entry.spec.required:
                self.log(
                    f"[launch] required node {entry.spec.fqn} ended (code {code}): shutting down"
                )
                return 0
            if entry.spec.respawn:
                if entry.ended_at is None:
                    entry.ended_at = now
                    self.log(
                        f"[launch] {entry.spec.fqn} ended (code {code}); respawning in "
                        f"{entry.spec.respawn_delay_s:g} s"
                    )
                elif now - entry.ended_at >= entry.spec.respawn_delay_s:
                    self.started.remove(entry)
                    self._start(entry.spec, entry.restarts + 1)
        return None

    def shutdown(self) -> None:
        """Stop every node in reverse start order, then the viewer and the bus."""
        for entry in reversed(self.started):
            try:
                entry.handle.stop()
            except Exception as exc:  # a node failing to stop never keeps the others running
                self.log(f"[launch] {entry.spec.fqn} did not stop cleanly: {exc}")
                continue
            # A node with its own thread (a spawner unloading its controllers) may still need
            # the bus, whose callbacks run here: spin until it ends, as roslaunch waits.
            end = time.monotonic() + _STOP_TIMEOUT_S
            while entry.handle.exit_code() is None and time.monotonic() < end:
                self.context.spin_once(0.02)
        # Every node is stopped: closing the viewer and the bus is all that is left. A Zenoh
        # session whose runtime panicked while peers went away can block in close() for good;
        # the launch then ends anyway, after saying so.
        line = (
            f"[launch] closing the viewer and the bus took over {_CLOSE_TIMEOUT_S:g} s; every "
            "node had stopped: exiting"
        )
        try:
            with ends_process_after(_CLOSE_TIMEOUT_S, line, exit_code=0):
                if self.gui is not None:
                    self.gui.close()
                if self.context is not None:
                    self.context.shutdown()
                if self._ros1 is not None:
                    self._ros1.close()
        finally:
            if self._node_log is not None:
                self._node_log.detach()


_STOP_TIMEOUT_S = 5.0
_CLOSE_TIMEOUT_S = 10.0


_OUTPUT_LOCK = threading.Lock()


def _write_line(text: str) -> None:
    """One whole line on stderr: nodes log from their own threads too."""
    with _OUTPUT_LOCK:
        sys.stderr.write(text + "\n")
        sys.stderr.flush()


class _Done:
    """A step that has nothing to run (a log line): done at once, with code 0."""

    def stop(self) -> None:
        pass

    def exit_code(self) -> int | None:
        return 0


def _process_spec(step: Any) -> NodeSpec:
    executable = step.command[0].rsplit("/", 1)[-1] if step.command else "process"
    return NodeSpec(
        "ros2", "", executable, executable, args=tuple(step.command[1:]), location=step.location
    )


class _Failed:
    """A node whose start failed: it counts as ended with code 1 (as a crashed process)."""

    def stop(self) -> None:
        pass

    def exit_code(self) -> int | None:
        return 1
