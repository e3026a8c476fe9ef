"""A TF frame that is no longer published, in headless Chromium: its axes are drawn in their
colours, then grey, then not at all (RViz's Frame Timeout, :mod:`.tf_fade`), with no /tf
arriving meanwhile (the viewer redraws a fading frame by itself).

The viewer runs on simulated time (``use_sim_time``, /clock published by the test), as beside a
simulator: the frame's age is what the test's clock says, so the grey stretch lasts until the
test moves the clock on, however long the page takes to draw and be looked at.
"""

from __future__ import annotations

import io
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from tests.viewer.conftest import VIEWPORT, open_viewer, save_shot, wait_for
from tests.viewer.fed_viewer import EMPTY_ROBOT
from tests.viewer.test_sensor_displays_browser import _look_at_origin, _project
from tests.viewer.test_tools_inprocess import on_loop

pytestmark = pytest.mark.browser

PROBE_XYZ = (0.0, 0.0, 1.5)  # where the probe frame is published, above the grid
SCALE = 8.0  # Marker Scale: axes 0.8 m long
FRAME_TIMEOUT_S = 10.0  # of simulated time
DRAW_TICK_S = 0.1  # simulated time a look moves on by while the frame is fresh


@pytest.fixture
def viewer(tmp_path: Path) -> Iterator[Viewer]:
    urdf = tmp_path / "frame_only.urdf"
    urdf.write_text(EMPTY_ROBOT)
    options = ViewerOptions(sources=(RobotSource(str(urdf)),), port=0, fixed_frame="map", tools=False)  # fmt: skip
    viewer = Viewer(options)
    viewer.start()
    yield viewer
    viewer.close()


def _publish_probe(viewer: Viewer) -> Any:
    """Publish the probe frame every 0.1 s of simulated time, stamped with it; returns the
    timer (cancel it: the frame then ages)."""
    from robomodel.runtime.msg import get_message_type

    TFMessage = get_message_type("tf2_msgs/msg/TFMessage")
    Stamped = get_message_type("geometry_msgs/msg/TransformStamped")
    assert viewer.context is not None
    context = viewer.context

    def start() -> Any:
        node = context.create_node("probe", parameters={"use_sim_time": True})
        publisher = node.create_publisher(TFMessage, "/tf", 10)

        def publish() -> None:
            tf = Stamped()
            stamp_ns = node.get_clock().now_ns()
            tf.header.frame_id, tf.child_frame_id = "map", "probe"
            tf.header.stamp.sec, tf.header.stamp.nanosec = divmod(stamp_ns, 10**9)
            tf.transform.translation.x, tf.transform.translation.y, tf.transform.translation.z = PROBE_XYZ  # fmt: skip
            tf.transform.rotation.w = 1.0
            publisher.publish(TFMessage(transforms=[tf]))

        publish()
        return node.create_timer(0.1, publish)

    return on_loop(viewer, start)


def _simulated_clock(viewer: Viewer) -> Callable[[float], None]:
    """Put the viewer's displays on simulated time; returns a function that publishes /clock
    at ``t_s`` and returns once the displays' node is at that time (its timers, the displays'
    drawing among them, have run)."""
    from robomodel.runtime.msg import Clock

    assert viewer.context is not None
    context = viewer.context
    node = viewer.displays.node

    def start() -> Any:
        node.set_parameters({"use_sim_time": True})
        return context.create_node("sim_clock").create_publisher(Clock, "/clock", 10)

    publisher = on_loop(viewer, start)

    def set_time(t_s: float) -> None:
        msg = Clock()
        msg.clock.sec, msg.clock.nanosec = divmod(round(t_s * 1e9), 10**9)
        on_loop(viewer, lambda: publisher.publish(msg))
        on_loop(viewer, lambda: None)  # the /clock delivery and the timers it made due ran
        assert node.get_clock().now_s() == pytest.approx(t_s)

    return set_time


def test_a_frame_no_longer_published_turns_grey_then_goes(viewer: Viewer, page: Any) -> None:
    open_viewer(page, viewer.url)
    (tf,) = (d for d in viewer.displays.displays if d.class_name == "TF")
    on_loop(viewer, lambda: tf.set_option("Marker Scale", SCALE))
    camera = _look_at_origin(viewer, (0.0, -6.0, 0.0))
    probed: list[Any] = []

    def probe_pixel() -> tuple[int, int] | None:
        """The page pixel of the middle of the probe's x axis, once it is inside the page."""
        canvas = page.locator("canvas").first.bounding_box()
        middle = np.array([PROBE_XYZ]) + np.array([[0.05 * SCALE, 0.0, 0.0]])
        (uv,) = _project(camera, canvas, middle)
        u, v = round(float(uv[0])), round(float(uv[1]))
        probed[:] = [(u, v), canvas, camera.position, camera.wxyz, camera.fov]
        inside = 1 <= u <= VIEWPORT["width"] - 2 and 1 <= v <= VIEWPORT["height"] - 2
        return (u, v) if inside else None

    u, v = wait_for(probe_pixel, what=lambda: f"the probe's pixel inside the page: {probed}")
    set_time = _simulated_clock(viewer)
    now_s = [100.0]  # simulated time [s]
    set_time(now_s[0])

    def colour() -> tuple[float, float, float]:
        # the 3 x 3 pixels around (u, v) only: a look costs a fraction of a whole-page shot
        clip = {"x": u - 1, "y": v - 1, "width": 3, "height": 3}
        patch = np.asarray(Image.open(io.BytesIO(page.screenshot(clip=clip))).convert("RGB"))
        r, g, b = (float(np.median(patch[..., k].astype(float))) for k in range(3))
        return r, g, b

    seen: list[tuple[float, float, float]] = []

    def looks(test: Any, tick_s: float = 0.0) -> bool:
        """Move simulated time on by ``tick_s`` (the displays draw), then look at the axis."""
        if tick_s:
            now_s[0] += tick_s
            set_time(now_s[0])
        seen[:] = [colour()]
        return bool(test(*seen[0]))

    def red(r: float, g: float, b: float) -> bool:
        return r > 100 and r > 2.5 * max(g, b)

    timer = _publish_probe(viewer)  # fresh until its red was seen, however long the page takes
    wait_for(lambda: looks(red, DRAW_TICK_S), what=lambda: f"red x axis ({seen})")
    on_loop(viewer, lambda: tf.set_option("Frame Timeout", FRAME_TIMEOUT_S))  # drawn anew
    wait_for(lambda: looks(red, DRAW_TICK_S), what=lambda: f"red x axis again ({seen})")
    save_shot(page, "tf_frame_fresh")
    on_loop(viewer, timer.cancel)  # no longer published: it ages from the next draw on
    looks(red, DRAW_TICK_S)  # the draw that saw its last transform
    # 0.72 of Frame Timeout old: grey (from two thirds) at alpha 0.84 over the page's white;
    # the clock stays there until the page shows it
    looks(lambda r, g, b: True, 0.72 * FRAME_TIMEOUT_S)
    grey = wait_for(
        lambda: looks(lambda r, g, b: max(r, g, b) - min(r, g, b) < 20 and 90 < r < 215),
        what=lambda: f"the x axis greyed ({seen})",
    )
    assert grey
    save_shot(page, "tf_frame_grey")
    looks(lambda r, g, b: True, 0.3 * FRAME_TIMEOUT_S)  # past Frame Timeout
    wait_for(lambda: "probe" not in tf.shown, what="the probe past its timeout")
    # the page's white where the axis was
    wait_for(lambda: looks(lambda r, g, b: min(r, g, b) > 250), what=lambda: f"the axis gone ({seen})")  # fmt: skip
    save_shot(page, "tf_frame_gone")
