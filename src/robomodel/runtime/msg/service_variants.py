"""Earlier layouts of ``controller_manager_msgs/srv/ListControllers`` within Jazzy.

``ControllerState`` changed twice during Jazzy's ros2_control releases (ros-controls/
ros2_control, ``controller_manager_msgs/msg/ControllerState.msg`` at the tags):

- 4.0.0 to 4.12.x: no ``exported_state_interfaces``, no ``is_async``, no ``update_rate``;
- 4.13.0 to 4.27.x: ``exported_state_interfaces`` added (#1021, "Export state interfaces from
  chainable controllers");
- 4.28.0 on: ``is_async`` and ``update_rate`` added (#2102) -- robomodel's
  :class:`~robomodel.runtime.msg.types.controller_manager_msgs.ControllerState`.

Each layout has its own RIHS01 hash, so rmw_zenoh keys each under its own service key: a
``ros2 control list_controllers`` of an older install only finds a server of its layout. The
controller manager offers every variant (one queryable each). The earlier ControllerState
classes are generated from the releases' ``.msg`` files (:mod:`.layouts.controller_manager_msgs`,
tools/gen_msgs.py); like the services here, they are not registered by type name (the name is
the current layout's) and are reached from here only.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.runtime.msg.layouts.controller_manager_msgs import (
    ControllerState_4_0,
    ControllerState_4_13,
)
from robomodel.runtime.msg.schema import Message, Seq, Service
from robomodel.runtime.msg.types.controller_manager_msgs import ControllerState

__all__ = ["LIST_CONTROLLERS_VARIANTS", "ListControllersVariant", "downgrade"]


def _service(state: type[Message], tag: str) -> type[Service]:
    """A ListControllers of ``state``'s layout (named as the real one, not registered)."""

    @dataclass(slots=True)
    class Request(Message):
        __fields__ = ()

    @dataclass(slots=True)
    class Response(Message):
        controller: list[Message] = field(default_factory=list)
        __fields__ = (("controller", Seq(state)),)

    class ListControllers(Service):
        pass

    # set after the classes exist, so that the registry by type name keeps the current layout
    for cls, name in ((Request, "Request"), (Response, "Response")):
        cls.__typename__ = f"controller_manager_msgs/srv/ListControllers_{name}"
        cls.__qualname__ = f"ListControllers_{tag}_{name}"
    ListControllers.__typename__ = "controller_manager_msgs/srv/ListControllers"
    ListControllers.Request = Request
    ListControllers.Response = Response
    return ListControllers


@dataclass(frozen=True, slots=True)
class ListControllersVariant:
    """One earlier layout: the ros2_control releases that use it, and its service type."""

    releases: str
    srv_type: type[Service]
    state_type: type[Message]


LIST_CONTROLLERS_VARIANTS = (
    ListControllersVariant("4.0-4.12", _service(ControllerState_4_0, "4_0"), ControllerState_4_0),
    ListControllersVariant(
        "4.13-4.27", _service(ControllerState_4_13, "4_13"), ControllerState_4_13
    ),
)


def downgrade(state: ControllerState, variant: ListControllersVariant) -> Message:
    """``state`` in ``variant``'s layout (the fields it lacks are left out)."""
    names = variant.state_type.field_names()
    return variant.state_type(**{n: getattr(state, n) for n in names})
