"""A TF frame that is no longer published, in headless Chromium: its axes are drawn in their
colours, then grey, then not at all (RViz's Frame Timeout, :mod:`.tf_fade`), with no /tf
arriving meanwhile (the viewer redraws a fading frame by itself)."""

from __future__ import annotations

import io
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from tests.timing import scaled
from tests.viewer.conftest import open_viewer, save_shot, wait_for
from tests.viewer.fed_viewer import EMPTY_ROBOT
from tests.viewer.test_sensor_displays_browser import _look_at_origin, _project
from tests.viewer.test_tools_inprocess import on_loop

pytestmark = pytest.mark.browser

PROBE_XYZ = (0.0, 0.0, 1.5)  # where the probe frame is published, above the grid
SCALE = 8.0  # Marker Scale: axes 0.8 m long


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
    """Publish the probe frame at 10 Hz, freshly stamped; returns the timer (cancel it: the
    frame then ages)."""
    from robomodel.runtime.msg import get_message_type

    TFMessage = get_message_type("tf2_msgs/msg/TFMessage")
    Stamped = get_message_type("geometry_msgs/msg/TransformStamped")
    assert viewer.context is not None
    context = viewer.context

    def start() -> Any:
        node = context.create_node("probe")
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


def test_a_frame_no_longer_published_turns_grey_then_goes(viewer: Viewer, page: Any) -> None:
    open_viewer(page, viewer.url)
    (tf,) = (d for d in viewer.displays.displays if d.class_name == "TF")
    on_loop(viewer, lambda: tf.set_option("Marker Scale", SCALE))
    camera = _look_at_origin(viewer, (0.0, -6.0, 0.0))
    canvas = page.locator("canvas").first.bounding_box()
    # the middle of the probe's x axis
    (uv,) = _project(camera, canvas, np.array([PROBE_XYZ]) + np.array([[0.05 * SCALE, 0.0, 0.0]]))
    u, v = round(float(uv[0])), round(float(uv[1]))

    def colour() -> tuple[float, float, float]:
        # the 3 x 3 pixels around (u, v) only: a look costs a fraction of a whole-page shot
        clip = {"x": u - 1, "y": v - 1, "width": 3, "height": 3}
        patch = np.asarray(Image.open(io.BytesIO(page.screenshot(clip=clip))).convert("RGB"))
        r, g, b = (float(np.median(patch[..., k].astype(float))) for k in range(3))
        return r, g, b

    seen: list[tuple[float, float, float]] = []
    looks_s: list[float] = []  # how long each look took (a screenshot's round trip) [s]

    def looks(test: Any) -> bool:
        start = time.monotonic()
        seen[:] = [colour()]
        looks_s.append(time.monotonic() - start)
        return bool(test(*seen[0]))

    timer = _publish_probe(viewer)  # fresh until its red was seen, however long the page takes
    wait_for(lambda: looks(lambda r, g, b: r > 100 and r > 2.5 * max(g, b)), what=lambda: f"red x axis ({seen})")  # fmt: skip
    for _ in range(3):  # the pace of the page's screenshots, with the frame fresh and drawn
        looks(lambda r, g, b: True)
    # The page shows the axis grey over about a fifth of Frame Timeout (its colour within 20 of
    # grey from 0.63 of it, its alpha over white lighter than 215 from 0.83): a timeout of 30
    # looks at the slowest pace seen (a look and wait_for's 0.1 s) gives that stretch about six
    # looks however busy the machine, where a fixed one would cost every run the slowest
    # machine's wait; at least 3 s, at most the 12 s (scaled) the test gave every page before.
    timeout_s = min(max(3.0, 30.0 * (max(looks_s[-3:]) + 0.1)), scaled(12.0))
    on_loop(viewer, lambda: tf.set_option("Frame Timeout", timeout_s))  # the axes drawn anew
    wait_for(lambda: looks(lambda r, g, b: r > 100 and r > 2.5 * max(g, b)), what=lambda: f"red x axis again ({seen})")  # fmt: skip
    save_shot(page, "tf_frame_fresh")
    on_loop(viewer, timer.cancel)  # no longer published: it ages from here
    grey = wait_for(
        lambda: looks(lambda r, g, b: max(r, g, b) - min(r, g, b) < 20 and 90 < r < 215),
        timeout_s=timeout_s + 10.0, what=lambda: f"the x axis greyed ({seen}; Frame Timeout {timeout_s:.1f} s)",
    )  # fmt: skip
    assert grey
    save_shot(page, "tf_frame_grey")
    wait_for(lambda: "probe" not in tf.shown, timeout_s=timeout_s + 10.0, what="the probe past its timeout")  # fmt: skip
    # the page's white where the axis was (the last of the fade, alpha near 0, is lighter grey)
    wait_for(lambda: looks(lambda r, g, b: min(r, g, b) > 250), what=lambda: f"the axis gone ({seen})")  # fmt: skip
    save_shot(page, "tf_frame_gone")
