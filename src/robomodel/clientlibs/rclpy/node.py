"""``rclpy.node.Node``: an rclpy node that is a robomodel runtime node (``.robomodel_node``).

Publishers, subscriptions, services, clients, timers, parameters, the clock and ``/rosout``
logging are the robomodel node's, so the node is on the graph as any robomodel node is
(rmw_zenoh's tokens on the Zenoh bus): ``ros2 node list``, ``ros2 topic echo`` and
``ros2 param`` of a real ROS 2 install see it. Callbacks run on an executor the node was added
to, as their callback groups allow; one that reaches another executor waits on the node.
"""

from __future__ import annotations

import collections
import copy
import functools
import inspect
import threading
from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.rclpy import exceptions as ex
from robomodel.clientlibs.rclpy import executors as _executors  # noqa: F401 (as rclpy's node:

# ``rclpy.executors`` is an attribute of the package once a node can be made)
from robomodel.clientlibs.rclpy._arguments import parse_ros_arguments
from robomodel.clientlibs.rclpy._support import interface, not_offered
from robomodel.clientlibs.rclpy.callback_groups import (
    CallbackGroup,
    MutuallyExclusiveCallbackGroup,
)
from robomodel.clientlibs.rclpy.client import Client
from robomodel.clientlibs.rclpy.clock import Clock, ROSClock
from robomodel.clientlibs.rclpy.event_handler import EventHandler, EventWatch
from robomodel.clientlibs.rclpy.guard_condition import GuardCondition
from robomodel.clientlibs.rclpy.logging import RcutilsLogger
from robomodel.clientlibs.rclpy.parameter import Parameter
from robomodel.clientlibs.rclpy.parameter import _Type as ParameterType
from robomodel.clientlibs.rclpy.publisher import Publisher
from robomodel.clientlibs.rclpy.qos import (
    HistoryPolicy,
    QoSProfile,
    as_robomodel_qos,
    qos_profile_services_default,
)
from robomodel.clientlibs.rclpy.service import Service
from robomodel.clientlibs.rclpy.subscription import Subscription
from robomodel.clientlibs.rclpy.task import Task
from robomodel.clientlibs.rclpy.timer import Rate, Timer
from robomodel.clientlibs.rclpy.utilities import get_default_context
from robomodel.runtime.names import NameError_
from robomodel.runtime.params import ParameterError, SetResult

if TYPE_CHECKING:
    from robomodel.clientlibs.rclpy.context import Context

__all__ = ["Node"]

_SetCallback = Callable[[list[Parameter]], Any]


def _int_qos(qos_profile: QoSProfile | int) -> QoSProfile:
    return qos_profile if isinstance(qos_profile, QoSProfile) else QoSProfile(depth=qos_profile)


class Node:
    """A node (``Node("talker")``, or a subclass as the ROS 2 tutorials write them).

    Args mirror rclpy's; ``cli_args`` are this node's ``--ros-args`` besides the context's.
    ``start_parameter_services=False`` is not offered.
    """

    PARAM_REL_TOL = 1e-6

    def __init__(
        self,
        node_name: str,
        *,
        context: Context | None = None,
        cli_args: Sequence[str] | None = None,
        namespace: str | None = None,
        use_global_arguments: bool = True,
        enable_rosout: bool = True,
        rosout_qos_profile: Any = None,
        start_parameter_services: bool = True,
        parameter_overrides: Sequence[Parameter] | None = None,
        allow_undeclared_parameters: bool = False,
        automatically_declare_parameters_from_overrides: bool = False,
        enable_logger_service: bool = False,
    ) -> None:
        if not start_parameter_services:
            not_offered("Node(start_parameter_services=False)")
        self._context = context or get_default_context()
        robomodel_context = self._context.robomodel  # NotInitializedException before init
        arguments = self._context.arguments if use_global_arguments else parse_ros_arguments([])
        local = parse_ros_arguments(list(cli_args or []))
        name = local.node_name(arguments.node_name(node_name))
        namespace = local.namespace(arguments.namespace(namespace, node_name), node_name)
        remappings = {**arguments.remappings(node_name), **local.remappings(node_name)}
        from robomodel.runtime.names import fully_qualified_node_name, validate_namespace

        try:
            fq_name = fully_qualified_node_name(name, namespace or "/")
        except NameError_ as exc:
            raise ex.InvalidNamespaceException(str(exc)) from None
        overrides = {**arguments.overrides(fq_name), **local.overrides(fq_name)}
        overrides.update({p.name: p.value for p in parameter_overrides or ()})
        try:
            self.robomodel_node = robomodel_context.create_node(
                name,
                validate_namespace(namespace or "/"),
                parameters=overrides,
                remappings=remappings,
                allow_undeclared_parameters=allow_undeclared_parameters,
                enable_rosout=enable_rosout and arguments.rosout and local.rosout,
            )
        except NameError_ as exc:
            raise ex.InvalidNodeNameException(str(exc)) from None
        self._overrides = overrides
        self._allow_undeclared = allow_undeclared_parameters
        self._unset: dict[str, ParameterType] = {}  # declared with a type or none, no value
        self._descriptors: dict[str, Any] = {}
        self._set_callbacks: list[_SetCallback] = []
        self._post_set_callbacks: list[Callable[[list[Parameter]], None]] = []
        self.robomodel_node.parameters.add_set_callback(self._run_set_callbacks)
        self.robomodel_node.parameters.add_post_set_callback(self._run_post_set_callbacks)
        self._pre_set_callbacks: list[Callable[[list[Parameter]], list[Parameter]]] = []
        self.robomodel_node.parameters.add_pre_set_callback(self._run_pre_set_callbacks)
        self.default_callback_group: CallbackGroup = MutuallyExclusiveCallbackGroup()
        self.executor: Any = None  # the rclpy Executor the node was last added to
        # deliveries that reached an executor not holding this node, for one that does
        self._parked: collections.deque[Callable[[], None]] = collections.deque()
        self._publishers: list[Publisher] = []
        self._subscriptions: list[Subscription] = []
        self._services: list[Service] = []
        self._clients: list[Client] = []
        self._timers: list[Timer] = []
        self._guards: list[GuardCondition] = []
        self._waitables: list[Any] = []
        self._clock = ROSClock(self.robomodel_node.get_clock)
        logger_name = fq_name.lstrip("/").replace("/", ".")
        robomodel_node = self.robomodel_node
        self._logger = RcutilsLogger(logger_name, rosout=lambda: robomodel_node.rosout)
        self._destroyed = False
        self._context.track_node(self)
        # as rclpy, whose node module imports it: ``rclpy.executors`` is there once a node is
        import robomodel.clientlibs.rclpy.executors  # noqa: F401

        if enable_logger_service:
            from robomodel.clientlibs.rclpy.logging_service import LoggingService

            self._logger_service = LoggingService(self)
        if automatically_declare_parameters_from_overrides:
            for pname, value in overrides.items():
                if not self.has_parameter(pname):
                    self.declare_parameter(pname, value)

    # -- names and context ------------------------------------------------------------------
    @property
    def context(self) -> Context:
        return self._context

    @property
    def handle(self) -> Any:
        not_offered("Node.handle (rcl's handle)")

    def get_name(self) -> str:
        return self.robomodel_node.name

    def get_namespace(self) -> str:
        return self.robomodel_node.namespace

    def get_fully_qualified_name(self) -> str:
        return self.robomodel_node.fully_qualified_name

    def get_logger(self) -> RcutilsLogger:
        return self._logger

    def get_clock(self) -> ROSClock:
        return self._clock

    def resolve_topic_name(self, topic: str, *, only_expand: bool = False) -> str:
        from robomodel.runtime.names import expand_topic_name

        node = self.robomodel_node
        if only_expand:
            return expand_topic_name(topic, node.name, node.namespace)
        return node.resolve_topic_name(topic)

    def resolve_service_name(self, service: str, *, only_expand: bool = False) -> str:
        return self.resolve_topic_name(service, only_expand=only_expand)

    # -- entities ----------------------------------------------------------------------------
    @property
    def publishers(self) -> Iterator[Publisher]:
        yield from self._publishers

    @property
    def subscriptions(self) -> Iterator[Subscription]:
        yield from self._subscriptions

    @property
    def services(self) -> Iterator[Service]:
        yield from self._services

    @property
    def clients(self) -> Iterator[Client]:
        yield from self._clients

    @property
    def timers(self) -> Iterator[Timer]:
        yield from self._timers

    @property
    def guards(self) -> Iterator[GuardCondition]:
        yield from self._guards

    @property
    def waitables(self) -> Iterator[Any]:
        yield from self._waitables

    def _dispatcher(
        self,
        group: CallbackGroup,
        callback: Callable[..., Any],
        *,
        coalesce: bool = False,
        depth: int = 0,
        entity: list[Any] | None = None,
    ) -> Callable[..., None]:
        """``callback`` as the bus calls it: handed to the spinning executor, which runs it as
        ``group`` allows; a coroutine function runs as a :class:`Task`. With ``coalesce`` (a
        timer) at most one call waits for its turn on another thread, as an rclpy timer is
        ready once however many periods passed while its group was busy.

        A call that reaches an executor this node was not added to is parked on the node
        until one it was added to spins: the newest ``depth`` calls (0: all; a timer's one).
        A user's group that gates its callbacks is asked about ``entity[0]`` (filled in once
        the entity is made) before each call and told after it."""
        context = self._context
        if inspect.iscoroutinefunction(callback):
            coroutine_function = callback

            def callback(*args: Any) -> None:
                task = Task(coroutine_function, args, executor=context)
                task._fails_spin = True
                task()

        made = entity if entity is not None else []
        if group.gates():
            ungated = callback

            def callback(*args: Any) -> None:
                subject = made[0] if made else None
                if not group.can_execute(subject) or not group.beginning_execution(subject):
                    return  # refused: dropped (rclpy's would stay ready until allowed)
                try:
                    ungated(*args)
                finally:
                    group.ending_execution(subject)

        waiting = threading.Lock()  # held while a call of a coalescing callback waits
        kept: collections.deque[tuple[Any, ...]] = collections.deque(
            maxlen=1 if coalesce else (depth or None)
        )
        node_parked = self._parked

        def run_waiting() -> None:
            waiting.release()
            callback()

        def unpark() -> None:
            try:
                args = kept.popleft()
            except IndexError:  # dropped: the depth was exceeded while parked
                return
            deliver(*args)

        def deliver(*args: Any) -> None:
            executor = context.dispatcher
            if executor is not None and not executor.owns(self):
                if kept.maxlen is None or len(kept) < kept.maxlen:
                    node_parked.append(unpark)  # one unpark per call kept
                kept.append(args)
                self._wake_owner()
                return
            if executor is None or not executor.hands_over:
                try:  # on the spinning thread, at once (no hand-over to pay for)
                    callback(*args)
                except Exception as exc:
                    if executor is None:
                        raise
                    executor.fail(exc)
            elif not coalesce:
                executor.dispatch(group, functools.partial(callback, *args), self, _first(made))
            elif waiting.acquire(blocking=False):
                executor.dispatch(group, run_waiting, self, _first(made))

        return deliver

    def _wake_owner(self) -> None:
        """Work was parked on this node: the executor holding it (spinning on another thread)
        runs it now rather than at the end of its wait."""
        owner = self.executor
        if owner is not None and owner.owns(self):
            owner.wake()

    def create_publisher(
        self,
        msg_type: Any,
        topic: str,
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: Any = None,
        qos_overriding_options: Any = None,
        publisher_class: Any = None,
    ) -> Publisher:
        """Publish ``msg_type`` on ``topic`` (relative names go in the node's namespace)."""
        if publisher_class is not None:
            not_offered("create_publisher(publisher_class=...)")
        group = callback_group or self.default_callback_group
        profile = self._overridden_qos(Publisher, topic, qos_profile, qos_overriding_options)
        handlers = event_callbacks.create_event_handlers(group) if event_callbacks else []
        publisher = Publisher(
            self.robomodel_node.create_publisher(msg_type, topic, profile.to_robomodel()),
            profile,
        )
        if handlers:
            watch = self._watch_events(
                group,
                handlers,
                matched_count=publisher.get_subscription_count,
                lost_count=lambda: 0,
                deadline_ns=profile.deadline_ns(),
            )
            publisher._watch(watch)
        self._publishers.append(publisher)
        return publisher

    def create_subscription(
        self,
        msg_type: Any,
        topic: str,
        callback: Callable[[Any], Any],
        qos_profile: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        event_callbacks: Any = None,
        qos_overriding_options: Any = None,
        raw: bool = False,
    ) -> Subscription:
        """Call ``callback(msg)`` with each message (of ``msg_type``, the class passed here;
        with ``raw``, the serialized message: its CDR bytes, as rmw hands them over)."""
        if _required_arguments(callback) > 1:
            not_offered("a subscription callback taking (msg, message_info)")
        group = callback_group or self.default_callback_group
        profile = self._overridden_qos(Subscription, topic, qos_profile, qos_overriding_options)
        handlers = event_callbacks.create_event_handlers(group) if event_callbacks else []
        kept = profile.depth if profile.history != HistoryPolicy.KEEP_ALL else 0
        made: list[Any] = []
        deliver = self._dispatcher(group, callback, depth=kept, entity=made)
        watch = None
        if handlers:
            watch = self._watch_events(
                group,
                handlers,
                matched_count=lambda: self._publisher_count(made[0]) if made else 0,
                lost_count=lambda: (
                    made[0].robomodel_subscription.get_messages_lost() if made else 0
                ),
                deadline_ns=profile.deadline_ns(),
            )
            if watch.deadline_ns:
                deliver = watch.noting(deliver)
        if raw:
            handle = self._raw_subscription(msg_type, topic, deliver, profile)
        else:
            handle = self.robomodel_node.create_subscription(
                msg_type, topic, deliver, profile.to_robomodel()
            )
        subscription = Subscription(handle, callback, group, profile)
        subscription.raw = raw
        if watch is not None:
            subscription._watch(watch)
        made.append(subscription)
        group.add_entity(subscription)
        self._subscriptions.append(subscription)
        return subscription

    def _publisher_count(self, subscription: Subscription) -> int:
        """The graph's publishers of the subscription's topic and type (its matches)."""
        info = self._graph().topics.get(subscription.topic_name)
        typename = subscription.msg_type.__typename__
        return sum(1 for e in info.publishers if e.type_name == typename) if info else 0

    def _watch_events(
        self,
        group: CallbackGroup,
        handlers: list[EventHandler],
        *,
        matched_count: Callable[[], int],
        lost_count: Callable[[], int],
        deadline_ns: int,
    ) -> EventWatch:
        """Poll an entity's events on the node's timer; their callbacks run in ``group``."""
        watch = EventWatch(
            handlers, matched_count=matched_count, lost_count=lost_count, deadline_ns=deadline_ns
        )

        def poll() -> None:
            for handler, status in watch.poll():
                handler.callback(status)

        timer = self.robomodel_node.create_timer(
            watch.period_s, self._dispatcher(group, poll, coalesce=True)
        )
        watch.on_stop(timer.cancel)
        return watch

    def _overridden_qos(
        self, entity_type: type, topic: str, qos_profile: QoSProfile | int, options: Any
    ) -> QoSProfile:
        """A copy of the profile, with the ``qos_overrides.<topic>.<entity>.<policy>``
        parameters that ``options`` (QoSOverridingOptions) asks for applied."""
        as_robomodel_qos(qos_profile)  # TypeError or ValueError for what is not a profile
        profile = copy.copy(_int_qos(qos_profile))
        if options is not None and options.policy_kinds:
            from robomodel.clientlibs.rclpy.qos_overriding_options import declare_qos_parameters

            declare_qos_parameters(
                entity_type, self, self.resolve_topic_name(topic), profile, options
            )
        return profile

    def _raw_subscription(
        self, msg_type: Any, topic: str, deliver: Callable[..., None], qos_profile: Any
    ) -> Any:
        """A subscription handing over each sample's serialized bytes, on a bus that has them
        (Zenoh's; the in-process bus passes objects, not bytes)."""
        from robomodel.runtime.node import Subscription as RobomodelSubscription

        node = self.robomodel_node
        create_raw = getattr(node.context.transport, "create_raw_subscription", None)
        if create_raw is None:
            not_offered("create_subscription(raw=True) on the in-process bus", "use Zenoh's")
        name = node.resolve_topic_name(topic)
        qos = as_robomodel_qos(qos_profile)
        handle = create_raw(
            node.fully_qualified_name, name, msg_type, qos, lambda payload, info: deliver(payload)
        )
        return RobomodelSubscription(name, msg_type, qos, handle)

    def create_service(
        self,
        srv_type: Any,
        srv_name: str,
        callback: Callable[[Any, Any], Any],
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
    ) -> Service:
        """Answer ``srv_name`` with ``callback(request, response) -> response``."""
        from robomodel.clientlibs.rclpy.service_introspection import Introspection
        from robomodel.runtime.transport.base import Deferred, request_being_served

        group = callback_group or self.default_callback_group
        context = self._context
        introspection = Introspection(
            self.robomodel_node, srv_type, self.robomodel_node.resolve_topic_name(srv_name)
        )

        def answer(request: Any, request_id: Any) -> Any:
            response = callback(request, srv_type.Response())
            introspection.publish(Introspection.RESPONSE_SENT, request_id, response)
            return response

        def serve(request: Any) -> Any:
            request_id = request_being_served.get()  # read now: the transport is calling
            introspection.publish(Introspection.REQUEST_RECEIVED, request_id, request)
            return handle(request, request_id)

        def handle(request: Any, request_id: Any) -> Any:
            executor = context.dispatcher
            if executor is not None and not executor.owns(self):
                return park(request, request_id)  # answered when an executor holding it spins
            if executor is None or not executor.hands_over:
                return answer(request, request_id)
            deferred = Deferred()

            def run() -> None:
                response = answer(request, request_id)
                context._post(lambda: deferred.resolve(response))

            executor.dispatch(group, run, self)
            return deferred

        def park(request: Any, request_id: Any) -> Any:
            deferred = Deferred()

            def unpark() -> None:
                response = handle(request, request_id)  # raising: the spin call raises it
                if isinstance(response, Deferred):
                    response.then(lambda result: context._post(lambda: deferred.resolve(result)))
                else:
                    context._post(lambda: deferred.resolve(response))

            self._parked.append(unpark)
            self._wake_owner()
            return deferred

        server = self.robomodel_node.create_service(srv_type, srv_name, serve)
        service = Service(server, callback, group, qos_profile, introspection)
        group.add_entity(service)
        self._services.append(service)
        return service

    def create_client(
        self,
        srv_type: Any,
        srv_name: str,
        *,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
    ) -> Client:
        group = callback_group or self.default_callback_group
        node = self.robomodel_node
        node.create_client(srv_type, srv_name)  # enters the type in the node's type cache
        from robomodel.clientlibs.rclpy.service_introspection import Introspection

        name = node.resolve_topic_name(srv_name)
        client = Client(
            self._context,
            node.fully_qualified_name,
            srv_type,
            name,
            group,
            qos_profile,
            taken=self._dispatcher(group, _response_taken, coalesce=True),
            introspection=Introspection(node, srv_type, name),
        )
        group.add_entity(client)
        self._clients.append(client)
        return client

    def create_timer(
        self,
        timer_period_sec: float,
        callback: Callable[[], Any],
        callback_group: CallbackGroup | None = None,
        clock: Clock | None = None,
        autostart: bool = True,
    ) -> Timer:
        """Call ``callback()`` every ``timer_period_sec`` seconds of the node's clock."""
        if clock is not None and clock is not self._clock:
            not_offered("create_timer(clock=...) with a clock other than the node's")
        group = callback_group or self.default_callback_group
        made: list[Any] = []
        timer = Timer(
            self.robomodel_node,
            self._dispatcher(group, callback, coalesce=True, entity=made),
            callback,
            group,
            round(timer_period_sec * 1e9),
            self._clock,
            autostart=autostart,
        )
        made.append(timer)
        group.add_entity(timer)
        self._timers.append(timer)
        return timer

    def create_rate(self, frequency: float, clock: Clock | None = None) -> Rate:
        return Rate(frequency, clock or self._clock, self._context)

    def create_guard_condition(
        self, callback: Callable[[], Any], callback_group: CallbackGroup | None = None
    ) -> GuardCondition:
        """A guard condition whose ``trigger()`` has this node's executor run ``callback()``."""
        group = callback_group or self.default_callback_group
        made: list[Any] = []
        guard = GuardCondition(
            callback,
            group,
            self._context,
            fire=None
            if callback is None
            else self._dispatcher(group, callback, coalesce=True, entity=made),
        )
        made.append(guard)
        group.add_entity(guard)
        self._guards.append(guard)
        return guard

    def destroy_guard_condition(self, guard: GuardCondition) -> bool:
        return self._destroy(self._guards, guard)

    def add_waitable(self, waitable: Any) -> None:
        not_offered("Node.add_waitable()")

    def destroy_publisher(self, publisher: Publisher) -> bool:
        return self._destroy(self._publishers, publisher)

    def destroy_subscription(self, subscription: Subscription) -> bool:
        return self._destroy(self._subscriptions, subscription)

    def destroy_service(self, service: Service) -> bool:
        return self._destroy(self._services, service)

    def destroy_client(self, client: Client) -> bool:
        return self._destroy(self._clients, client)

    def destroy_timer(self, timer: Timer) -> bool:
        return self._destroy(self._timers, timer)

    def destroy_rate(self, rate: Rate) -> bool:
        rate.destroy()
        return True

    @staticmethod
    def _destroy(entities: list[Any], entity: Any) -> bool:
        if entity not in entities:
            return False
        entities.remove(entity)
        entity.destroy()
        return True

    def destroy_node(self) -> None:
        """Destroy every entity of the node and leave the graph."""
        if self._destroyed:
            return
        self._destroyed = True
        if self.executor is not None:  # as rclpy: a destroyed node leaves its executor
            self.executor.remove_node(self)
        self._parked.clear()
        for client in self._clients:
            client.destroy()
        for timer in self._timers:
            timer.destroy()
        for subscription in self._subscriptions:
            if subscription.raw:  # the robomodel node does not know it
                subscription.destroy()
        self._publishers.clear()
        self._subscriptions.clear()
        self._services.clear()
        self._clients.clear()
        self._timers.clear()
        for guard in self._guards:
            guard.destroy()
        self._guards.clear()
        self._context.untrack_node(self)
        if self._context.ok():
            context = self._context.robomodel
            if self.robomodel_node in context.nodes:
                context.nodes.remove(self.robomodel_node)
            self.robomodel_node.destroy()

    def __enter__(self) -> Node:
        return self

    def __exit__(self, *exc: object) -> None:
        self.destroy_node()

    # -- graph -------------------------------------------------------------------------------
    def _graph(self) -> Any:
        return self._context.robomodel.transport.graph(0.0)

    def get_node_names(self) -> list[str]:
        return [name for name, _ in self.get_node_names_and_namespaces()]

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        out = []
        for fq_name in sorted(self._graph().nodes):
            namespace, _, name = fq_name.rpartition("/")
            out.append((name, namespace or "/"))
        return out

    def get_fully_qualified_node_names(self) -> list[str]:
        return sorted(self._graph().nodes)

    def get_topic_names_and_types(self, no_demangle: bool = False) -> list[tuple[str, list[str]]]:
        topics = self._graph().topics
        return [(name, sorted(info.types)) for name, info in sorted(topics.items())]

    def get_service_names_and_types(self) -> list[tuple[str, list[str]]]:
        services = self._graph().services
        return [(name, sorted(info.types)) for name, info in sorted(services.items())]

    def _by_node(
        self, node_name: str, node_namespace: str, kind: str
    ) -> list[tuple[str, list[str]]]:
        from robomodel.runtime.names import fully_qualified_node_name

        wanted = fully_qualified_node_name(node_name, node_namespace)
        graph = self._graph()
        if wanted not in graph.nodes:
            raise ex.InvalidNodeNameException(f"node '{wanted}' is not in the graph")
        found: dict[str, set[str]] = {}
        table = graph.services if kind in ("servers", "clients") else graph.topics
        for name, info in table.items():
            for endpoint in getattr(info, kind):
                if endpoint.node == wanted:
                    found.setdefault(name, set()).add(endpoint.type_name)
        return [(name, sorted(types)) for name, types in sorted(found.items())]

    def get_publisher_names_and_types_by_node(
        self, node_name: str, node_namespace: str, no_demangle: bool = False
    ) -> list[tuple[str, list[str]]]:
        return self._by_node(node_name, node_namespace, "publishers")

    def get_subscriber_names_and_types_by_node(
        self, node_name: str, node_namespace: str, no_demangle: bool = False
    ) -> list[tuple[str, list[str]]]:
        return self._by_node(node_name, node_namespace, "subscribers")

    def get_service_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        return self._by_node(node_name, node_namespace, "servers")

    def get_client_names_and_types_by_node(
        self, node_name: str, node_namespace: str
    ) -> list[tuple[str, list[str]]]:
        return self._by_node(node_name, node_namespace, "clients")

    def count_publishers(self, topic_name: str) -> int:
        info = self._graph().topics.get(self.resolve_topic_name(topic_name))
        return len(info.publishers) if info else 0

    def count_subscribers(self, topic_name: str) -> int:
        info = self._graph().topics.get(self.resolve_topic_name(topic_name))
        return len(info.subscribers) if info else 0

    def count_services(self, service_name: str) -> int:
        info = self._graph().services.get(self.resolve_service_name(service_name))
        return len(info.servers) if info else 0

    def count_clients(self, service_name: str) -> int:
        info = self._graph().services.get(self.resolve_service_name(service_name))
        return len(info.clients) if info else 0

    def _endpoints(self, topic_name: str, kind: str, no_mangle: bool) -> list[Any]:
        from robomodel.clientlibs.rclpy.qos import from_robomodel
        from robomodel.clientlibs.rclpy.topic_endpoint_info import (
            TopicEndpointInfo,
            TopicEndpointTypeEnum,
        )

        name = topic_name if no_mangle else self.resolve_topic_name(topic_name)
        info = self._graph().topics.get(name)
        endpoint_type = (
            TopicEndpointTypeEnum.PUBLISHER if kind == "publishers"
            else TopicEndpointTypeEnum.SUBSCRIPTION
        )  # fmt: skip
        found = []
        for endpoint in getattr(info, kind) if info else ():
            namespace, _, node_name = endpoint.node.rpartition("/")
            found.append(TopicEndpointInfo(
                node_name=node_name, node_namespace=namespace or "/",
                topic_type=endpoint.type_name, topic_type_hash=endpoint.type_hash,
                endpoint_type=endpoint_type, qos_profile=from_robomodel(endpoint.qos),
            ))  # fmt: skip
        return found

    def get_publishers_info_by_topic(self, topic_name: str, no_mangle: bool = False) -> list[Any]:
        """The publishers of ``topic_name`` in the graph (``TopicEndpointInfo``)."""
        return self._endpoints(topic_name, "publishers", no_mangle)

    def get_subscriptions_info_by_topic(
        self, topic_name: str, no_mangle: bool = False
    ) -> list[Any]:
        """The subscriptions of ``topic_name`` in the graph (``TopicEndpointInfo``)."""
        return self._endpoints(topic_name, "subscribers", no_mangle)

    def wait_for_node(self, fully_qualified_node_name: str, timeout: float) -> bool:
        """Wait up to ``timeout`` seconds for a node to be in the graph."""
        import time

        deadline = time.monotonic() + timeout
        while self._context.ok():
            if fully_qualified_node_name in self._graph().nodes:
                return True
            if time.monotonic() >= deadline:
                return False
            self._context.wait_shutdown(0.02)
        return False

    # -- parameters --------------------------------------------------------------------------
    def declare_parameter(
        self,
        name: str,
        value: Any = None,
        descriptor: Any = None,
        ignore_override: bool = False,
    ) -> Parameter:
        """Declare ``name`` with ``value`` (a value, or a ``Parameter.Type`` for a parameter
        without one yet); an override (``-p``, a file, ``parameter_overrides``) wins."""
        store = self.robomodel_node.parameters
        if store.has(name) and not (self._allow_undeclared and name not in self._descriptors):
            raise ex.ParameterAlreadyDeclaredException([name])
        if name in self._unset:
            raise ex.ParameterAlreadyDeclaredException([name])
        if isinstance(value, Parameter):
            value = value.value
        if descriptor is None:
            descriptor = interface("rcl_interfaces.msg", "ParameterDescriptor")()
        wanted_type: ParameterType | None = value if isinstance(value, Parameter.Type) else None
        if wanted_type is not None:
            value = None
        if ignore_override or name not in self._overrides:
            if value is None:
                self._unset[name] = wanted_type or Parameter.Type.NOT_SET
                self._descriptors[name] = descriptor
                return Parameter(name, Parameter.Type.NOT_SET, None)
            initial = value
        else:
            initial = self._overrides[name]
            if value is None:
                value = initial
        _plain = Parameter(name, value=value).value
        self._check_range(name, descriptor, initial)
        try:
            if ignore_override and name in self._overrides:
                got = store.declare(name, _plain, description=descriptor.description,
                                    read_only=bool(descriptor.read_only))  # fmt: skip
                store.set({name: _plain})
            else:
                got = self.robomodel_node.declare_parameter(
                    name, _plain, description=descriptor.description,
                    read_only=bool(descriptor.read_only),
                )  # fmt: skip
        except ParameterError as exc:
            raise ex.InvalidParameterTypeException(Parameter(name, value=value), str(exc)) from None
        self._descriptors[name] = descriptor
        return Parameter(name, value=got)

    def declare_parameters(
        self, namespace: str, parameters: Sequence[tuple[Any, ...]], ignore_override: bool = False
    ) -> list[Parameter]:
        """Declare several: tuples of (name,), (name, value) or (name, value, descriptor)."""
        declared = []
        for entry in parameters:
            name = f"{namespace}.{entry[0]}" if namespace else entry[0]
            value = entry[1] if len(entry) > 1 else None
            descriptor = entry[2] if len(entry) > 2 else None
            declared.append(self.declare_parameter(name, value, descriptor, ignore_override))
        return declared

    def undeclare_parameter(self, name: str) -> None:
        not_offered("Node.undeclare_parameter()")

    def has_parameter(self, name: str) -> bool:
        return name in self._unset or self.robomodel_node.parameters.has(name)

    def get_parameter(self, name: str) -> Parameter:
        if name in self._unset:
            if self._unset[name] != Parameter.Type.NOT_SET:
                raise ex.ParameterUninitializedException(name)
            return Parameter(name, Parameter.Type.NOT_SET, None)
        store = self.robomodel_node.parameters
        if not store.has(name):
            if self._allow_undeclared:
                return Parameter(name, Parameter.Type.NOT_SET, None)
            raise ex.ParameterNotDeclaredException(name)
        return Parameter(name, value=store.get(name))

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        if alternative_value is None:
            alternative_value = Parameter(name, Parameter.Type.NOT_SET)
        if not self.has_parameter(name) or name in self._unset:
            return alternative_value
        return self.get_parameter(name)

    def get_parameters(self, names: Sequence[str]) -> list[Parameter]:
        return [self.get_parameter(name) for name in names]

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        """Parameters under ``prefix.``, keyed by the rest of their name."""
        start = f"{prefix}." if prefix else ""
        store = self.robomodel_node.parameters
        return {n[len(start) :]: Parameter(n, value=store.get(n)) for n in store.names(start)}

    def describe_parameter(self, name: str) -> Any:
        if not self.has_parameter(name):
            raise ex.ParameterNotDeclaredException(name)
        descriptor = (
            self._descriptors.get(name) or interface("rcl_interfaces.msg", "ParameterDescriptor")()
        )
        descriptor.name = name
        descriptor.type = int(self.get_parameter(name).type_) if name not in self._unset else 0
        return descriptor

    def describe_parameters(self, names: Sequence[str]) -> list[Any]:
        return [self.describe_parameter(name) for name in names]

    def set_descriptor(self, name: str, descriptor: Any, alternative_value: Any = None) -> Any:
        not_offered("Node.set_descriptor()")

    def set_parameters(self, parameter_list: Sequence[Parameter]) -> list[Any]:
        """Set each parameter on its own; one ``SetParametersResult`` per parameter."""
        return [self._set([parameter]) for parameter in parameter_list]

    def set_parameters_atomically(self, parameter_list: Sequence[Parameter]) -> Any:
        """Set all or none; one ``SetParametersResult``."""
        return self._set(list(parameter_list))

    def _set(self, parameters: list[Parameter]) -> Any:
        result_class = interface("rcl_interfaces.msg", "SetParametersResult")
        changes: dict[str, Any] = {}
        for parameter in parameters:
            name = parameter.name
            if not self.has_parameter(name) and not self._allow_undeclared:
                raise ex.ParameterNotDeclaredException(name)
            descriptor = self._descriptors.get(name)
            if descriptor is not None and descriptor.read_only:
                raise ex.ParameterImmutableException(name)
            wanted = self._unset.get(name)
            if wanted not in (None, Parameter.Type.NOT_SET) and parameter.type_ != wanted:
                return result_class(successful=False, reason=(
                    f"Wrong parameter type, expected '{wanted.name}' got '{parameter.type_.name}'"
                ))  # fmt: skip
            reason = self._range_error(name, descriptor, parameter.value)
            if reason:
                return result_class(successful=False, reason=reason)
            changes[name] = parameter.value
        store = self.robomodel_node.parameters
        for name in [n for n in changes if n in self._unset]:  # their first value declares them
            callbacks_ok = self._run_set_callbacks({name: changes[name]})
            if not callbacks_ok.successful:
                return result_class(successful=False, reason=callbacks_ok.reason)
            descriptor = self._descriptors.get(name)
            store.declare(
                name, changes.pop(name), description=getattr(descriptor, "description", "")
            )
            del self._unset[name]
            self._run_post_set_callbacks({name: store.get(name)})
        if not changes:
            return result_class(successful=True, reason="")
        result = self.robomodel_node.set_parameters(changes)
        return result_class(successful=result.successful, reason=result.reason)

    def _check_range(self, name: str, descriptor: Any, value: Any) -> None:
        reason = self._range_error(name, descriptor, value)
        if reason:
            raise ex.InvalidParameterValueException(name, value, reason)

    def _range_error(self, name: str, descriptor: Any, value: Any) -> str:
        """Why ``value`` is outside the descriptor's integer or floating point range, or ""."""
        if descriptor is None or isinstance(value, bool):
            return ""
        for kind, ranges in (("integer", descriptor.integer_range),
                             ("floating point", descriptor.floating_point_range)):  # fmt: skip
            if not ranges or not isinstance(value, (int, float)):
                continue
            bounds = ranges[0]
            low, high, step = bounds.from_value, bounds.to_value, bounds.step
            if not low <= value <= high:
                return f"Parameter {name} out of {kind} range [{low}, {high}]"
            if step and value != high:
                steps = (value - low) / step
                if abs(steps - round(steps)) > self.PARAM_REL_TOL:
                    return f"Parameter {name} is not a step of {step} from {low}"
        return ""

    def add_on_set_parameters_callback(self, callback: _SetCallback) -> None:
        """``callback(list[Parameter]) -> SetParametersResult`` may refuse a change."""
        self._set_callbacks.insert(0, callback)

    def remove_on_set_parameters_callback(self, callback: _SetCallback) -> None:
        self._set_callbacks.remove(callback)

    def add_post_set_parameters_callback(self, callback: Callable[[list[Parameter]], None]) -> None:
        self._post_set_callbacks.append(callback)

    def remove_post_set_parameters_callback(
        self, callback: Callable[[list[Parameter]], None]
    ) -> None:
        self._post_set_callbacks.remove(callback)

    def add_pre_set_parameters_callback(
        self, callback: Callable[[list[Parameter]], list[Parameter]]
    ) -> None:
        """``callback(list[Parameter]) -> list[Parameter]`` changes what a set (this node's or a
        remote one: ``ros2 param set``) will set, before it is checked; the newest first."""
        self._pre_set_callbacks.insert(0, callback)

    def remove_pre_set_parameters_callback(
        self, callback: Callable[[list[Parameter]], list[Parameter]]
    ) -> None:
        self._pre_set_callbacks.remove(callback)

    def _run_pre_set_callbacks(self, changes: Any) -> dict[str, Any]:
        """As rclpy: each callback sees the parameters asked for; what they return, together,
        is set (a later entry of a name wins)."""
        if not self._pre_set_callbacks:
            return dict(changes)
        parameters = [Parameter(name, value=value) for name, value in changes.items()]
        modified: list[Parameter] = []
        for callback in list(self._pre_set_callbacks):
            modified.extend(callback(parameters))
        return {parameter.name: parameter.value for parameter in modified}

    def _run_set_callbacks(self, changes: Any) -> SetResult:
        parameters = [Parameter(name, value=value) for name, value in changes.items()]
        for callback in list(self._set_callbacks):
            result = callback(parameters)
            if not result.successful:
                return SetResult(False, str(result.reason))
        return SetResult(True)

    def _run_post_set_callbacks(self, changes: Any) -> None:
        parameters = [Parameter(name, value=value) for name, value in changes.items()]
        for callback in list(self._post_set_callbacks):
            callback(parameters)


def _required_arguments(callback: Callable[..., Any]) -> int:
    """How many positional arguments ``callback`` needs (0 when it cannot be told)."""
    try:
        signature = inspect.signature(callback)
    except (TypeError, ValueError):
        return 0
    return sum(
        1
        for p in signature.parameters.values()
        if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) and p.default is p.empty
    )


def _response_taken() -> None:
    """A client's response came (its future is done already): run on the executor holding the
    node, as rclpy's executor takes the response, so that a waiting ``spin_once`` returns."""


def _first(made: list[Any]) -> Any:
    """The entity a callback belongs to, once made (None before)."""
    return made[0] if made else None
