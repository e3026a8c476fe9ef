"""The context: one executor, one clock, one transport, and the nodes that share them."""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.clock import Clock, ManualClock, SystemClock
from robomodel.runtime.executor import Executor
from robomodel.runtime.msg import Message
from robomodel.runtime.msg.schema import Service
from robomodel.runtime.node import Node
from robomodel.runtime.params import load_parameters_file
from robomodel.runtime.transport.base import Graph, Transport
from robomodel.runtime.transport.inproc import InprocTransport

__all__ = ["BUSES", "Context"]

BUSES = ("inproc", "zenoh", "ros1")


class Context:
    """Where nodes live and run.

    Args:
        bus: ``"inproc"`` (deterministic, in this process; the library default), ``"zenoh"``
            (other robomodel processes and ROS 2 nodes: rmw_zenoh's wire) or ``"ros1"`` (a ROS 1
            master's graph: XML-RPC and TCPROS).
        clock: The time source; pass a :class:`ManualClock` and call :meth:`advance` for
            reproducible runs. Defaults to wall-clock time.
        domain_id: Keeps groups of processes apart (like ROS_DOMAIN_ID); Zenoh only.
        connect: Zenoh endpoints to connect to (``tcp/host:port``).
        listen: Extra Zenoh endpoints to listen on.
        master: The ROS 1 master's URI (``ros1``; default ``ROS_MASTER_URI``, else
            http://localhost:11311/).
    """

    def __init__(
        self,
        bus: str = "inproc",
        *,
        clock: Clock | None = None,
        domain_id: int | None = None,
        connect: Sequence[str] = (),
        listen: Sequence[str] = (),
        master: str | None = None,
    ) -> None:
        self.bus = bus
        self.clock = clock or SystemClock()
        self.executor = Executor()
        self.transport: Transport
        if bus == "inproc":
            self.transport = InprocTransport(self.executor)
        elif bus == "zenoh":
            from robomodel.runtime.transport.zenoh_bus import ZenohTransport

            self.transport = ZenohTransport(
                self.executor, domain_id=domain_id, connect=connect, listen=listen
            )
        elif bus == "ros1":
            from robomodel.runtime.transport.ros1_bus import Ros1Transport

            self.transport = Ros1Transport(self.executor, master=master)
        else:
            raise RobomodelError(f"unknown bus '{bus}'; choose one of: {', '.join(BUSES)}")
        self.nodes: list[Node] = []
        self._closed = False

    def create_node(
        self,
        name: str,
        namespace: str = "/",
        *,
        parameters: Mapping[str, Any] | None = None,
        parameter_files: Sequence[str | os.PathLike[str]] = (),
        remappings: Mapping[str, str] | None = None,
        allow_undeclared_parameters: bool = False,
        enable_rosout: bool = True,
    ) -> Node:
        """Create a node; ``parameters`` and files override declared defaults, as --ros-args."""
        from robomodel.runtime.names import fully_qualified_node_name

        overrides: dict[str, Any] = {}
        fq_name = fully_qualified_node_name(name, namespace)
        for path in parameter_files:
            overrides.update(load_parameters_file(path, fq_name))
        overrides.update(parameters or {})
        node = Node(
            self,
            name,
            namespace,
            parameter_overrides=overrides,
            remappings=remappings,
            allow_undeclared_parameters=allow_undeclared_parameters,
            enable_rosout=enable_rosout,
        )
        self.nodes.append(node)
        return node

    # -- running ---------------------------------------------------------------------------
    def spin_once(self, timeout_s: float = 0.0) -> int:
        return self.executor.spin_once(timeout_s)

    def spin(
        self, *, duration_s: float | None = None, until: Callable[[], bool] | None = None
    ) -> None:
        self.executor.spin(duration_s=duration_s, until=until)

    def advance(self, dt_s: float) -> None:
        """Advance a :class:`ManualClock` by ``dt_s``, running timers and callbacks in order."""
        if not isinstance(self.clock, ManualClock):
            raise RobomodelError("advance() needs a context created with clock=ManualClock()")
        self.executor.advance(self.clock, dt_s)

    def graph(self, timeout_s: float = 1.0) -> Graph:
        return self.transport.graph(timeout_s)

    def call_service(
        self,
        name: str,
        srv_type: type[Service],
        request: Message | None = None,
        timeout_s: float = 2.0,
    ) -> Any:
        """Call service ``name`` (offered by any process on the bus, or this one) and return
        its response; :class:`ServiceCallError` when none comes within ``timeout_s``."""
        if request is None:
            request = srv_type.Request()
        return self.transport.call_service(name, srv_type, request, timeout_s)

    def shutdown(self) -> None:
        if self._closed:
            return
        self._closed = True
        for node in self.nodes:
            node.destroy()
        self.executor.stop()
        self.transport.close()

    def __enter__(self) -> Context:
        return self

    def __exit__(self, *exc: object) -> None:
        self.shutdown()
