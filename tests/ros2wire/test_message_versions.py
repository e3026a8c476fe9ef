"""ListControllers under every Jazzy layout: the controller manager answers a
client of ros2_control 4.0-4.12, 4.13-4.27 and 4.28+ each in its own layout.

The layouts' reference is the upstream files at the release tags (``interface_versions/``,
hashed by rosbags), not robomodel's classes; the calls go through rmw_zenoh's keys, which
carry each layout's service type hash.
"""

from __future__ import annotations

import re
import signal
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from robomodel.runtime import Context
from robomodel.runtime.msg.schema import Message, Service
from robomodel.runtime.msg.service_variants import LIST_CONTROLLERS_VARIANTS
from robomodel.runtime.msg.typehash import type_hash
from robomodel.runtime.msg.types import controller_manager_msgs
from tests.conftest import EXAMPLES, ROBOMODEL, past_the_bus_line, unique_domain
from tests.timing import scaled

typesys = pytest.importorskip("rosbags.typesys")

VERSIONS = Path(__file__).with_name("interface_versions")
ARM = EXAMPLES / "two_link_arm/urdf/two_link_arm.urdf.xacro"
ARM_CONTROLLERS = EXAMPLES / "two_link_arm/config/position_controllers.yaml"
LAYOUTS: list[tuple[str, type[Service]]] = [
    ("4.12.0", LIST_CONTROLLERS_VARIANTS[0].srv_type),
    ("4.13.0", LIST_CONTROLLERS_VARIANTS[1].srv_type),
    ("4.28.0", controller_manager_msgs.ListControllers),
]


def _upstream(tag: str) -> object:
    """A type store holding controller_manager_msgs as release ``tag`` defines it."""
    store = typesys.get_typestore(typesys.Stores.ROS2_JAZZY)
    root = VERSIONS / f"ros2_control-{tag}" / "controller_manager_msgs"
    types = {}
    for name in ("ChainConnection", "ControllerState"):
        text = (root / "msg" / f"{name}.msg").read_text()
        types.update(typesys.get_types_from_msg(text, f"controller_manager_msgs/msg/{name}"))
    request, response = re.split(r"^---[ \t]*$", (root / "srv/ListControllers.srv").read_text(),
                                 flags=re.MULTILINE)  # fmt: skip
    for part, text in (("Request", request), ("Response", response)):
        parsed = typesys.get_types_from_msg(
            text, f"controller_manager_msgs/msg/ListControllers_{part}"
        )
        types[f"controller_manager_msgs/srv/ListControllers_{part}"] = parsed.popitem()[1]
    store.register(types)
    return store


@pytest.mark.parametrize(("tag", "srv_type"), LAYOUTS)
def test_each_layout_is_the_release_s(tag: str, srv_type: type[Service]) -> None:
    store = _upstream(tag)
    state: type[Message] = dict(srv_type.Response.__fields__)["controller"].item  # type: ignore[attr-defined]
    _, fields = store.fielddefs["controller_manager_msgs/msg/ControllerState"]  # type: ignore[attr-defined]
    assert state.field_names() == tuple(name for name, _ in fields)
    response = "controller_manager_msgs/srv/ListControllers_Response"
    assert type_hash(srv_type.Response) == store.hash_rihs01(response)  # type: ignore[attr-defined]


def test_the_layouts_have_three_service_hashes() -> None:
    assert len({type_hash(srv_type) for _, srv_type in LAYOUTS}) == 3


@pytest.fixture
def arm_control() -> Iterator[str]:
    domain = unique_domain()
    proc = subprocess.Popen(
        [*ROBOMODEL, "control", "run", str(ARM), "--controllers", str(ARM_CONTROLLERS),
         "--no-view", "--domain-id", domain],
        stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    assert proc.stderr is not None and "controller manager" in past_the_bus_line(proc.stderr)
    yield domain
    proc.send_signal(signal.SIGINT)
    proc.wait(scaled(10))


def test_every_layout_is_answered_in_its_own(arm_control: str) -> None:
    from robomodel.cli._bus import wait_for_peers

    with Context("zenoh", domain_id=int(arm_control)) as ctx:
        wait_for_peers(ctx)
        # the peers are seen before every queryable of theirs is (a busy machine)
        deadline = time.monotonic() + scaled(20)
        while time.monotonic() < deadline:
            offered = ctx.graph(timeout_s=scaled(2)).services.get(
                "/controller_manager/list_controllers"
            )
            if offered is not None and len(offered.servers) == 3:
                break
            time.sleep(0.1)
        for tag, srv_type in LAYOUTS:
            reply = ctx.call_service(
                "/controller_manager/list_controllers", srv_type, timeout_s=scaled(10)
            )
            assert isinstance(reply, srv_type.Response), tag
            states = {c.name: c for c in reply.controller}  # type: ignore[attr-defined]
            assert states["joint1_position_controller"].state == "active", tag
            has_rate = "update_rate" in type(states["joint1_position_controller"]).field_names()
            assert has_rate == (tag == "4.28.0")
        servers = (
            ctx.graph(timeout_s=scaled(10)).services["/controller_manager/list_controllers"].servers
        )
        assert len(servers) == 3  # one queryable (and SS token) per layout
