"""``rclpy.client.Client``: calls a service over robomodel's transport.

``call_async`` sends the request from a thread of its own (the transport's call blocks) and
completes the returned future from there; its done callbacks run on the executor, and a
``spin_once`` waiting then returns, as rclpy's does after taking the response. ``call``
waits on the calling thread, so it works whether or not another thread spins (rclpy needs one
spinning; robomodel does not).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy._support import not_offered
from robomodel.clientlibs.rclpy.task import Future

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.callback_groups import CallbackGroup
    from robomodel.clientlibs.rclpy.clock import Clock
    from robomodel.clientlibs.rclpy.context import Context
    from robomodel.clientlibs.rclpy.qos import QoSProfile
    from robomodel.clientlibs.rclpy.service_introspection import (
        Introspection,
        ServiceIntrospectionState,
    )
    from robomodel.runtime.msg.schema import Service as ServiceType

__all__ = ["Client"]

_FOREVER_S = 24 * 3600.0  # rclpy's call_async has no timeout
_POLL_S = 0.02


class Client:
    """A client of ``srv_name`` (made by ``Node.create_client``)."""

    def __init__(
        self,
        context: Context,
        node_name: str,
        srv_type: type[ServiceType],
        srv_name: str,
        callback_group: CallbackGroup,
        qos_profile: QoSProfile,
        taken: Callable[[], None] | None = None,
        *,
        introspection: Introspection,
    ) -> None:
        self.context = context
        # Posted when a response came: the executor holding the client's node counts it as a
        # callback run, as rclpy's runs the client's (a loop of spin_once until the future is
        # done ends). None: nothing to tell.
        self._taken = taken
        self.srv_type = srv_type
        self.srv_name = srv_name
        self.callback_group = callback_group
        self.qos_profile = qos_profile
        self._node_name = node_name
        self._pending: set[Future] = set()
        self._destroyed = False
        self._introspection = introspection

    @property
    def service_name(self) -> str:
        return self.srv_name

    def _call(self, request: Any, timeout_s: float) -> Any:
        """The response, with the introspection events of the call: REQUEST_SENT as the
        transport numbers the request (or, on a bus without request ids, once it returned)."""
        from robomodel.runtime.transport.base import request_sent

        if self._destroyed:
            raise RuntimeError(f"client of '{self.srv_name}' was destroyed")
        introspection = self._introspection
        sent: list[Any] = []

        def told(request_id: Any) -> None:
            sent.append(request_id)
            introspection.publish(introspection.REQUEST_SENT, request_id, request)

        token = request_sent.set(told)
        try:
            response = self.context.robomodel.transport.call_service(
                self.srv_name, self.srv_type, request, timeout_s, node=self._node_name
            )
        finally:
            request_sent.reset(token)
        if not sent:
            told(None)
        introspection.publish(introspection.RESPONSE_RECEIVED, sent[0], response)
        return response

    def call_async(self, request: Any) -> Future:
        """Send ``request``; the future's result is the response (or the error it got)."""
        future = Future(executor=self.context)
        self._pending.add(future)

        def work() -> None:
            try:
                response = self._call(request, _FOREVER_S)
            except Exception as exc:
                future.set_exception(exc)
            else:
                future.set_result(response)
            finally:
                self._pending.discard(future)
                if self._taken is not None:
                    self.context._post(self._taken)

        threading.Thread(target=work, name=f"rclpy call {self.srv_name}", daemon=True).start()
        return future

    def call(self, request: Any, timeout_sec: float | None = None) -> Any:
        """The response; None if none came within ``timeout_sec`` (None: wait for ever)."""
        from robomodel.runtime.transport.base import ServiceCallError

        timeout_s = _FOREVER_S if timeout_sec is None else float(timeout_sec)
        try:
            return self._call(request, timeout_s)
        except ServiceCallError as exc:
            if "within" in str(exc) or "after" in str(exc):
                return None
            raise

    def remove_pending_request(self, future: Future) -> None:
        """Forget ``future``: it is cancelled (a late response is dropped)."""
        self._pending.discard(future)
        future.cancel()

    def service_is_ready(self) -> bool:
        """Whether a server of the service is in the graph now."""
        graph = self.context.robomodel.transport.graph(0.0)
        info = graph.services.get(self.srv_name)
        return bool(info and info.servers)

    def wait_for_service(self, timeout_sec: float | None = None) -> bool:
        """Wait until a server is in the graph; False after ``timeout_sec`` (None: for ever)."""
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        while self.context.ok():
            if self.service_is_ready():
                return True
            if deadline is not None and time.monotonic() >= deadline:
                return False
            self.context.wait_shutdown(_POLL_S)
        return False

    def configure_introspection(
        self,
        clock: Clock,
        service_event_qos_profile: QoSProfile,
        introspection_state: ServiceIntrospectionState,
    ) -> None:
        """Publish this client's events on ``<service>/_service_event`` as the state says
        (stamped by ``clock``)."""
        self._introspection.configure(clock, service_event_qos_profile, introspection_state)

    @property
    def handle(self) -> Any:
        not_offered("Client.handle (rcl's handle)")

    def destroy(self) -> None:
        self._introspection.destroy()
        self._destroyed = True
        for future in list(self._pending):
            future.cancel()
        self._pending.clear()

    def __enter__(self) -> Client:
        return self

    def __exit__(self, *exc: object) -> None:
        self.destroy()
