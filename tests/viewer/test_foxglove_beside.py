"""The viewer of a robot beside a Foxglove client on foxglove_bridge, on Zenoh: the viewer's
joint sliders publish ``/joint_states``, ``robomodel run foxglove_bridge foxglove_bridge``
offers it, and @foxglove/ws-protocol's FoxgloveClient with @foxglove/rosmsg2-serialization
(tests/bridges/foxglove_client.js) decodes the position the page's slider set. The picture of
both side by side is the documentation's (docs/howto/bridges.md)."""

from __future__ import annotations

import base64
import html
import json
import os
import subprocess
from collections.abc import Callable
from pathlib import Path
from typing import Any

from tests.bridges.started import wait_started
from tests.bridges.test_foxglove_clients import _end, node_client, results
from tests.conftest import EXAMPLES, ROBOMODEL, free_port, unique_domain
from tests.timing import scaled, wait_until
from tests.viewer.conftest import VIEWPORT, ViewerProcess, open_viewer, save_shot, type_into

URDF = EXAMPLES / "two_link_arm" / "urdf" / "two_link_arm.urdf"


def _at_0_9(log: Path) -> dict[str, Any] | None:
    """The client's first decoded /joint_states with joint2 at 0.9 rad, if one came."""
    for message in results(log).get("message", []):
        position = message["msg"]["position"]  # a Float64Array, as JSON: {"0": ..., "1": ...}
        if abs(float(position["1"]) - 0.9) < 1e-9:
            return message  # type: ignore[no-any-return]
    return None


def test_the_viewer_beside_a_foxglove_client(
    viewer: Callable[..., ViewerProcess], page: Any, browser: Any, tmp_path: Path
) -> None:
    domain, port = unique_domain(), free_port()
    shown = viewer(URDF, "--bus", "zenoh", "--domain-id", domain)
    env = {**os.environ, "ROS_PACKAGE_PATH": str(EXAMPLES)}
    log = tmp_path / "bridge.log"
    clients: list[subprocess.Popen[str]] = []
    bridge = subprocess.Popen(
        [*ROBOMODEL, "run", "--domain-id", domain, "foxglove_bridge", "foxglove_bridge",
         "--ros-args", "-p", f"port:={port}"],
        stdout=log.open("w"), stderr=subprocess.STDOUT, env=env, start_new_session=True,
    )  # fmt: skip
    try:
        wait_started(bridge, log, "listening at")
        plan = {"subscribe": "/joint_states", "every": True}  # each message the client decodes
        clients.append(node_client(f"ws://127.0.0.1:{port}", plan, tmp_path / "client.log"))
        open_viewer(page, shown.url)
        type_into(page, "joint2", "0.9")
        said = tmp_path / "client.log"
        message = wait_until(
            lambda: _at_0_9(said), 60,
            what=lambda: f"joint2 at 0.9 rad at the client: {said.read_text()[-2000:]}",
        )  # fmt: skip
    finally:
        for proc in [*clients, bridge]:
            _end(proc)
    assert message["schemaName"] == "sensor_msgs/msg/JointState" and message["encoding"] == "cdr"
    assert message["msg"]["name"] == ["joint1", "joint2"]
    msg = message["msg"]
    msg["position"] = [msg["position"][k] for k in sorted(msg["position"], key=int)]
    shot = base64.b64encode(save_shot(page, "foxglove_viewer").read_bytes()).decode()
    text = json.dumps(msg, indent=2)
    beside = browser.new_page(
        viewport={"width": VIEWPORT["width"] + 420, "height": VIEWPORT["height"]}
    )
    try:
        beside.set_content(
            "<body style='margin:0;display:flex;font:13px monospace;background:#fff'>"
            f"<img src='data:image/png;base64,{shot}'>"
            "<div style='padding:12px;border-left:1px solid #ccc'>"
            f"<b>Foxglove client</b><br>ws://127.0.0.1:{port} &middot; /joint_states<br>"
            f"{html.escape(message['schemaName'])} ({message['encoding']})"
            f"<pre>{html.escape(text)}</pre></div></body>"
        )
        beside.locator("img").evaluate("(img) => img.decode()", timeout=scaled(10_000))
        save_shot(beside, "foxglove_joint_states")
    finally:
        beside.close()
