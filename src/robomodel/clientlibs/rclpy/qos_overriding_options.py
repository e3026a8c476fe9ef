"""``rclpy.qos_overriding_options``: QoS policies a user overrides with parameters.

``create_publisher(..., qos_overriding_options=QoSOverridingOptions.with_default_policies())``
declares read-only parameters ``qos_overrides.<topic>.publisher.<policy>`` (``subscription``
for a subscription; ``publisher_<id>`` with an ``entity_id``), valued from ``-p`` / a params
file when given, else from the profile, and the entity gets the profile they make; the
optional callback then accepts or refuses it (:class:`InvalidQosOverridesError`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any, Protocol

from robomodel.clientlibs.rclpy._support import interface
from robomodel.clientlibs.rclpy.duration import Duration
from robomodel.clientlibs.rclpy.exceptions import ParameterAlreadyDeclaredException
from robomodel.clientlibs.rclpy.parameter import Parameter
from robomodel.clientlibs.rclpy.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    LivelinessPolicy,
    QoSPolicyKind,
    QoSProfile,
    ReliabilityPolicy,
)

__all__ = [
    "InvalidQosOverridesError",
    "QoSOverridingOptions",
    "QosCallbackType",
    "declare_qos_parameters",
]


class InvalidQosOverridesError(Exception):
    """The overriding callback refused the profile the parameters made."""


def __getattr__(name: str) -> Any:
    # rclpy's alias of rcl_interfaces' SetParametersResult, of the user's message flavour
    if name == "QosCallbackResult":
        return interface("rcl_interfaces.msg", "SetParametersResult")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


QosCallbackType = Callable[[QoSProfile], Any]

_ENUMS: dict[QoSPolicyKind, Any] = {
    QoSPolicyKind.HISTORY: HistoryPolicy,
    QoSPolicyKind.RELIABILITY: ReliabilityPolicy,
    QoSPolicyKind.DURABILITY: DurabilityPolicy,
    QoSPolicyKind.LIVELINESS: LivelinessPolicy,
}
_DURATIONS = (
    QoSPolicyKind.DEADLINE,
    QoSPolicyKind.LIFESPAN,
    QoSPolicyKind.LIVELINESS_LEASE_DURATION,
)


class QoSOverridingOptions:
    """Which policies get a parameter, the callback that validates the result, and an id to
    tell apart two entities of one topic."""

    def __init__(
        self,
        policy_kinds: Iterable[QoSPolicyKind],
        *,
        callback: QosCallbackType | None = None,
        entity_id: str | None = None,
    ) -> None:
        self._policy_kinds = tuple(policy_kinds)
        self._callback = callback
        self._entity_id = entity_id

    @property
    def policy_kinds(self) -> tuple[QoSPolicyKind, ...]:
        return self._policy_kinds

    @property
    def callback(self) -> QosCallbackType | None:
        return self._callback

    @property
    def entity_id(self) -> str | None:
        return self._entity_id

    @classmethod
    def with_default_policies(
        cls, *, callback: QosCallbackType | None = None, entity_id: str | None = None
    ) -> QoSOverridingOptions:
        """History, depth and reliability (rclpy's defaults)."""
        return cls(
            (QoSPolicyKind.HISTORY, QoSPolicyKind.DEPTH, QoSPolicyKind.RELIABILITY),
            callback=callback,
            entity_id=entity_id,
        )


class ParameterHolder(Protocol):
    """What the QoS parameters need of the rclpy Node making the entity."""

    def declare_parameter(
        self, name: str, value: Any = None, descriptor: Any = None, ignore_override: bool = False
    ) -> Parameter: ...

    def get_parameter(self, name: str) -> Parameter: ...


def declare_qos_parameters(
    entity_type: type,
    node: ParameterHolder,
    topic_name: str,
    qos: QoSProfile,
    options: QoSOverridingOptions,
) -> None:
    """Declare the parameters ``options`` asks for on ``node`` and apply them to ``qos`` (the
    entity's own copy): ``entity_type`` is rclpy's Publisher or Subscription class, ``node`` the
    rclpy Node making the entity."""
    from robomodel.clientlibs.rclpy.publisher import Publisher

    entity = "publisher" if issubclass(entity_type, Publisher) else "subscription"
    suffix = "" if options.entity_id is None else f"_{options.entity_id}"
    descriptor_class = interface("rcl_interfaces.msg", "ParameterDescriptor")
    for policy in options.policy_kinds:
        if policy in (QoSPolicyKind.INVALID, QoSPolicyKind.AVOID_ROS_NAMESPACE_CONVENTIONS):
            continue
        if policy is QoSPolicyKind.LIFESPAN and entity == "subscription":
            continue  # a subscription has no lifespan (rclpy leaves it out)
        policy_name = policy.name.lower()
        name = f"qos_overrides.{topic_name}.{entity}{suffix}.{policy_name}"
        descriptor = descriptor_class(
            description=f"{policy_name} for {entity} `{topic_name}` with id `{options.entity_id}`",
            read_only=True,
        )
        try:
            parameter = node.declare_parameter(name, _parameter_value(qos, policy), descriptor)
        except ParameterAlreadyDeclaredException:
            parameter = node.get_parameter(name)
        _apply(qos, policy, parameter.value, name)
    if options.callback is not None:
        result = options.callback(qos)
        if not result.successful:
            raise InvalidQosOverridesError(
                f"Provided QoS overrides for {entity} `{topic_name}` with id "
                f"`{options.entity_id}`, are not valid: {result.reason}"
            )


def _parameter_value(qos: QoSProfile, policy: QoSPolicyKind) -> str | int | bool:
    value = getattr(qos, policy.name.lower())
    if policy in _ENUMS:
        if value.name == "UNKNOWN":
            raise ValueError("User provided QoS profile is invalid")
        name: str = value.name.lower()
        return name
    if isinstance(value, Duration):
        return value.nanoseconds
    return int(value) if not isinstance(value, bool) else value


def _apply(qos: QoSProfile, policy: QoSPolicyKind, value: Any, name: str) -> None:
    if policy in _ENUMS:
        enum = _ENUMS[policy]
        try:
            value = enum[str(value).upper()]
        except KeyError:
            valid = ", ".join(m.name.lower() for m in enum)
            raise RuntimeError(
                f"Unexpected QoS override for policy `{policy.name.lower()}` "
                f"(parameter {name}): `{value}`; valid: {valid}"
            ) from None
    elif policy in _DURATIONS:
        value = Duration(nanoseconds=value)
    setattr(qos, policy.name.lower(), value)
