"""The rqt tools through the page (headless Chromium) on a viewer in this process.

The steering pad publishes a Twist, the plot draws a series, the parameter editor changes a
parameter of another node, and a LaserScan published here is drawn in the scene (by the
LaserScan display the viewer adds for the graph's scan topic).
"""

from __future__ import annotations

import io
import math
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest
from PIL import Image

from robomodel.runtime.msg import Header, LaserScan, Twist
from robomodel.runtime.node import Node
from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from tests.conftest import EXAMPLES
from tests.timing import scaled
from tests.viewer.conftest import (
    changed_fraction,
    changed_view,
    gui_row,
    new_page,
    open_viewer,
    save_shot,
    scene_region,
    screenshot,
    settle,
    slider_input,
    type_into,
    wait_for,
)
from tests.viewer.test_tools_inprocess import on_loop

pytestmark = pytest.mark.browser
shares_the_page = pytest.mark.xdist_group("tools_browser_simplebot")  # one worker: one page


@pytest.fixture(scope="module")
def simplebot_page(browser: Any) -> Iterator[tuple[Viewer, Any]]:
    """The simplebot's viewer and one page on it, for the tests of its tools: a page's first
    frames (software WebGL compiling its shaders, the scene's first load) cost more CPU than a
    test's own work. Each test opens its own tool's folder and makes nodes of its own names."""
    source = RobotSource(str(EXAMPLES / "simplebot_description/urdf/simplebot.urdf.xacro"))
    viewer = Viewer(ViewerOptions(sources=(source,), port=0))
    viewer.start()
    try:
        with new_page(browser) as page:
            open_viewer(page, viewer.url)
            yield viewer, page
    finally:
        viewer.close()


def _open(page: Any, folder: str) -> None:
    page.get_by_text(folder, exact=True).click()


@shares_the_page
def test_steering_pad_publishes_and_plot_draws_the_series(
    simplebot_page: tuple[Viewer, Any],
) -> None:
    simplebot, page = simplebot_page
    assert simplebot.context is not None
    context = simplebot.context
    twists: list[Twist] = []
    on_loop(
        simplebot,
        lambda: context.create_node("base").create_subscription(
            Twist, "/diff_drive_controller/cmd_vel_unstamped", twists.append
        ),
    )
    _open(page, "Robot Steering")
    type_into(page, "Steering topic", "/diff_drive_controller/cmd_vel_unstamped", simplebot.server)
    box = slider_input(page, "Linear x [m/s]")
    box.fill("0.5")
    box.press("Enter")
    wait_for(lambda: twists and twists[-1].linear.x == 0.5, what="a Twist from the page")
    _open(page, "Plot")
    # the chart shows the last Window [s]: 10 s passed between Stop's last sample and the
    # chart's screenshot on a loaded machine, leaving the chart empty
    window = gui_row(page, "Window [s]").locator("input:not([type=hidden])").first
    window.fill("300")
    window.press("Enter")
    wait_for(lambda: simplebot.tools.plot.window_s.value == 300, what="the chart's window 300 s")
    wait_for(
        lambda: "/diff_drive_controller/cmd_vel_unstamped" in simplebot.tools.tools.topics,
        what="the topic in the graph",
    )
    type_into(page, "Field", "/diff_drive_controller/cmd_vel_unstamped/linear/x", simplebot.server)
    page.get_by_text("Add series", exact=True).click()
    chart = page.locator(".uplot canvas").first
    chart.wait_for()
    page.get_by_text("/diff_drive_controller/cmd_vel_unstamped/linear/x").first.wait_for()
    wait_for(lambda: len(simplebot.tools.plot.data.series[0].values) > 10, what="samples")
    page.get_by_text("Stop", exact=True).click()
    wait_for(lambda: twists[-1].linear.x == 0.0, what="Stop to send zero")
    chart.scroll_into_view_if_needed()

    def blue_pixels() -> int:
        # the series' colour (#1f77b4) where the line is drawn, once the page has drawn the
        # chart's data (a page on a loaded machine is seconds behind the server's 10 Hz redraw)
        image = np.asarray(Image.open(io.BytesIO(chart.screenshot())).convert("RGB")).astype(int)
        return int((np.abs(image - np.array([0x1F, 0x77, 0xB4])).max(axis=2) < 40).sum())

    wait_for(lambda: blue_pixels() > 50, what=lambda: f"the line drawn: {blue_pixels()} pixels")
    save_shot(page, "tools_steering_plot")


@shares_the_page
def test_parameter_editor_and_laser_scan_in_the_scene(
    simplebot_page: tuple[Viewer, Any],
) -> None:
    simplebot, page = simplebot_page
    assert simplebot.context is not None
    context = simplebot.context

    def make_node() -> tuple[Node, Any]:
        node = context.create_node("tuned")
        node.declare_parameter("pid.p", 100.0)
        return node, node.create_publisher(LaserScan, "/scan", 10)

    node, scan_pub = on_loop(simplebot, make_node)
    _open(page, "Parameters")
    wait_for(lambda: "/tuned" in simplebot.tools.parameters.node_dropdown.options)
    page.locator("input[value='(choose a node)']:not([type=hidden])").click()
    page.get_by_role("option", name="/tuned", exact=True).click()
    page.get_by_text("pid.p", exact=True).wait_for()
    type_into(page, "pid.p", "42.5")
    wait_for(lambda: node.get_parameter("pid.p") == 42.5, what="pid.p set from the page")
    page.get_by_text("set to").wait_for()
    save_shot(page, "tools_parameters")
    # A ring of returns 1 m around base_link: drawn where the grid and background were.
    before = settle(page)
    ranges = [1.0] * 360
    scan = LaserScan(
        Header(frame_id="base_link"),
        angle_min=-math.pi,
        angle_max=math.pi,
        angle_increment=2 * math.pi / 360,
        range_min=0.05,
        range_max=10.0,
        ranges=ranges,
    )
    wait_for(lambda: "LaserScan" in simplebot.displays_panel.follower.added, what="the display")
    laser = simplebot.displays_panel.follower.added["LaserScan"]

    def drawn() -> bool:  # published until the display has subscribed and drawn it
        on_loop(simplebot, lambda: scan_pub.publish(scan))
        return laser.node("points") is not None

    wait_for(drawn, what="the scan drawn")
    changed_view(page, before, what="the ring of returns in the scene")
    save_shot(page, "tools_laser_scan")


def test_demo_simplebot_in_the_wall_world_driven_by_the_steering_pad(page: Any) -> None:
    """The make demo job: robomodel launch of simplebot_control's simplebot_demo.launch (the
    simulator, spawn_model, the controller spawner, rqt_robot_steering), steered from the page."""
    import os
    import subprocess

    from tests.conftest import ROBOMODEL
    from tests.viewer.conftest import domain_id, settle, start_launch_viewer

    domain = domain_id(41)
    env = {**os.environ, "ROS_PACKAGE_PATH": str(EXAMPLES)}
    launch, url, errors = start_launch_viewer(
        "simplebot_control", "simplebot_demo.launch", domain=domain, env=env
    )
    try:
        open_viewer(page, url)
        _open(page, "Robot Steering")
        topic = gui_row(page, "Steering topic").locator("input:not([type=hidden])").first
        wait_for(
            lambda: topic.input_value() == "/simplebot_controller/cmd_vel",
            what="the diff-drive topic",
        )
        try:
            wait_for(
                lambda: any("Started controllers" in line for line in errors),
                timeout_s=60,
                what="the spawner to start the controllers",
            )
        except BaseException:
            raise AssertionError(
                f"the spawner did not start the controllers in 60 s (launch running: "
                f"{launch.poll() is None}); its output:\n{''.join(errors[-60:])}"
            ) from None
        before = settle(page)
        box = slider_input(page, "Linear x [m/s]")
        box.fill("0.2")
        box.press("Enter")

        def moved() -> Any:  # one shot: a driving robot never gives settle() two equal ones
            image = scene_region(screenshot(page))
            return (image,) if changed_fraction(before, image) > 0.004 else None

        try:
            wait_for(moved, timeout_s=40, what="the simplebot to drive in the page")
        except BaseException:
            save_shot(page, "demo_simplebot_not_driving")
            raise AssertionError(
                f"the simplebot did not drive in the page (launch running: "
                f"{launch.poll() is None}); its output:\n{''.join(errors[-40:])}"
            ) from None
        # Stopped before the wall (2 m ahead): against it, the wheels would slip on and the
        # odometry, which places the robot as in RViz, would draw it behind the wall.
        page.get_by_text("Stop", exact=True).click()
        settle(page)
        save_shot(page, "demo_simplebot_driving")
        # The robot is drawn where its odometry says only if world -> odom (the simulator's
        # /tf_static) and odom -> base_link connect for a late joiner, as for the viewer.
        tf = subprocess.run(
            [*ROBOMODEL, "tf", "world", "base_link", "--once",
             "--timeout", f"{scaled(20):.1f}", "--domain-id", domain],
            capture_output=True, text=True, timeout=scaled(60),
        )  # fmt: skip
        assert tf.returncode == 0, tf.stderr[-2000:]
        x_m = float(tf.stdout.split("Translation: [")[1].split(",")[0])
        assert 0.05 < x_m < 1.5, tf.stdout  # it drove forward, and stopped short of the wall
        _pause_and_step_from_the_simulation_folder(page)
    finally:
        launch.terminate()
        launch.wait(timeout=scaled(30))


def _pause_and_step_from_the_simulation_folder(page: Any) -> None:
    """Gazebo's bar: the status shows sim time and RTF; Pause holds it; Step adds N steps."""
    import re

    _open(page, "Simulation")
    status = page.get_by_text(re.compile("real-time factor"))

    def sim_time() -> float | None:
        text = status.first.inner_text() if status.count() else ""
        found = re.search(r"Sim time ([0-9.]+) s", text)
        return float(found.group(1)) if found else None

    wait_for(sim_time, what="the sim time in the Simulation folder")
    page.get_by_role("button", name="Pause").click()
    shown = page.get_by_text(re.compile("real-time factor|/gazebo/pause_physics"))
    wait_for(lambda: "paused" in shown.first.inner_text(),
             what=lambda: f"the paused status (shown: {shown.first.inner_text()!r})")  # fmt: skip
    held = sim_time()
    assert held is not None
    type_into(page, "Steps", "500")  # the last update in 50 ms (Pause was long before): sent
    page.get_by_role("button", name="Step").click()
    wait_for(
        lambda: (t := sim_time()) is not None and abs(t - (held + 0.5)) < 1e-6,
        what="500 steps of 1 ms",
    )
    save_shot(page, "demo_simulation_paused")
    page.get_by_role("button", name="Play").click()
    wait_for(lambda: "paused" not in status.first.inner_text(), what="the physics running again")
