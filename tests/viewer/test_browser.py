"""`robomodel view` in headless Chromium: drawn, sliders, /tf, reload, errors, several robots.

Each test starts the real command, loads the page in Debian's Chromium (software WebGL) and
looks at pixels: the robot is where the background would otherwise be, a slider moved in the
page moves the drawing and the published /tf. Screenshots are kept in build/viewer-screenshots/.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.conftest import EXAMPLES, ROBOMODEL, example_robot_data_dir
from tests.timing import scaled
from tests.viewer.conftest import (
    ViewerProcess,
    changed_fraction,
    changed_view,
    domain_id,
    flip_checkbox,
    gui_row,
    open_viewer,
    save_shot,
    settle,
    slider_input,
    slider_thumb,
    toggle_checkbox,
    wait_for,
)
from tests.viewer.robots import write_arm

pytestmark = pytest.mark.browser


def test_simplebot_is_drawn_with_sliders_and_frames(
    viewer: Callable[..., ViewerProcess], page: Any
) -> None:
    view = viewer(EXAMPLES / "simplebot_description/urdf/simplebot.urdf.xacro")
    open_viewer(page, view.url)
    page.get_by_text("left_wheel_joint").wait_for()
    page.get_by_text("right_wheel_joint").wait_for()
    with_robot = settle(page)
    save_shot(page, "simplebot")
    toggle_checkbox(page, "Visual Enabled")
    # The robot covers pixels that are background (or grid) when its visuals are hidden.
    changed_view(page, with_robot, what="the robot's visuals hidden")
    # Randomize moves the sliders (and the wheels); Center brings them back to zero.
    toggle_checkbox(page, "Visual Enabled")
    page.get_by_text("Randomize").click()
    wait_for(
        lambda: float(slider_input(page, "left_wheel_joint").input_value()) != 0.0,
        what="Randomize to move the sliders",
    )
    page.get_by_text("Center").click()
    wait_for(
        lambda: float(slider_input(page, "left_wheel_joint").input_value()) == 0.0,
        what="Center to bring the sliders back",
    )


class TfProbe:
    """Listens to /tf over Zenoh in the test process (as another ROS process would)."""

    def __init__(self, domain: str) -> None:
        from robomodel.runtime import Context
        from robomodel.runtime.tf_listener import TransformListener

        self.context = Context("zenoh", domain_id=int(domain))
        self.buffer = TransformListener(self.context.create_node("probe")).buffer
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        while not self._stop.is_set():
            self.context.spin_once(0.05)

    def angle_x(self, target: str, source: str) -> float | None:
        """Rotation angle about x of ``source`` in ``target`` [rad], None before any /tf."""
        try:
            qx, _, _, qw = self.buffer.lookup_transform(target, source).rotation_xyzw
        except Exception:
            return None
        return float(2 * np.arctan2(qx, qw))

    def wait_angle(self, value: float) -> None:
        def reached() -> bool:
            angle = self.angle_x("base_link", "link1")
            return angle is not None and abs(angle - value) < 1e-3

        wait_for(reached, what=f"/tf of joint1 at {value} rad")

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=scaled(5))
        self.context.shutdown()


@pytest.fixture
def tf_probe() -> Iterator[Callable[[str], TfProbe]]:
    probes: list[TfProbe] = []

    def make(domain: str) -> TfProbe:
        probes.append(TfProbe(domain))
        return probes[-1]

    yield make
    for probe in probes:
        probe.close()


def test_slider_moves_drawing_and_published_tf(
    viewer: Callable[..., ViewerProcess],
    page: Any,
    tmp_path: Path,
    tf_probe: Callable[[str], TfProbe],
) -> None:
    domain = domain_id(1)
    probe = tf_probe(domain)
    view = viewer(write_arm(tmp_path), "--bus", "zenoh", "--domain-id", domain)
    open_viewer(page, view.url)
    before = settle(page)
    probe.wait_angle(0.0)
    box = slider_input(page, "joint1")
    box.fill("1.2")
    box.press("Enter")
    probe.wait_angle(1.2)
    changed_view(page, before, what="the arm drawn at joint1 = 1.2")
    save_shot(page, "arm_joint1_1.2")
    # The slider's thumb moved too: keyboard End takes it to the upper limit (2 rad).
    slider_thumb(page, "joint1").focus()
    page.keyboard.press("End")
    probe.wait_angle(2.0)
    assert float(box.input_value()) == pytest.approx(2.0)


def test_reload_keeps_slider_values_and_errors_keep_last_model(
    viewer: Callable[..., ViewerProcess], page: Any, tmp_path: Path
) -> None:
    path = write_arm(tmp_path)
    view = viewer(path)
    open_viewer(page, view.url)
    box = slider_input(page, "joint1")
    box.fill("0.8")
    box.press("Enter")
    thin = settle(page)
    write_arm(tmp_path, width=0.6)  # a much wider link1
    wait_for(
        lambda: changed_fraction(thin, settle(page, 5)) > 0.002,
        what="the reloaded (wider) arm to be drawn",
    )
    save_shot(page, "arm_reloaded_wide")
    assert float(slider_input(page, "joint1").input_value()) == pytest.approx(0.8)
    wide = settle(page)
    path.write_text(path.read_text().replace("</robot>", "<link name='broken'>"))
    error = page.get_by_text("showing the last good model")
    error.wait_for(timeout=scaled(15_000))
    status = page.get_by_text("arm.urdf:").first.locator("xpath=..").inner_text()
    assert "error:" in status and "arm.urdf:" in status
    save_shot(page, "arm_broken")
    assert changed_fraction(wide, settle(page)) < 0.002  # the last good model stays
    write_arm(tmp_path, width=0.15)
    wait_for(
        lambda: page.get_by_text("showing the last good model").count() == 0,
        what="the error to clear",
    )


def test_missing_mesh_is_listed_and_the_rest_drawn(
    viewer: Callable[..., ViewerProcess], page: Any, tmp_path: Path
) -> None:
    extra = """<link name="escape"><visual><geometry>
      <mesh filename="package://simplebot_description/../../etc/passwd"/></geometry></visual></link>
      <joint name="escape_joint" type="fixed"><parent link="base_link"/><child link="escape"/></joint>"""
    path = write_arm(tmp_path, mesh="meshes/nothere.stl", extra=extra)
    view = viewer(path, "--package", f"simplebot_description={EXAMPLES / 'simplebot_description'}")
    open_viewer(page, view.url)
    page.get_by_text("2 mesh(es) not drawn").wait_for(timeout=scaled(15_000))
    text = page.get_by_text("2 mesh(es) not drawn").locator("xpath=..").inner_text()
    assert "file not found" in text
    assert "escapes package" in text
    drawn = settle(page)
    save_shot(page, "arm_missing_mesh")
    toggle_checkbox(page, "Visual Enabled")
    changed_view(page, drawn, what="the visuals hidden")


def test_two_prefixed_robots_in_one_scene(viewer: Callable[..., ViewerProcess], page: Any) -> None:
    xacro = EXAMPLES / "example_description/urdf/example.urdf.xacro"
    view = viewer(xacro, xacro, "--prefix", "robot1/", "--prefix", "robot2/")
    open_viewer(page, view.url)
    page.get_by_text("drawn beside it").wait_for(timeout=scaled(15_000))
    dropdown = page.locator("input[value='robot1/base_footprint']")
    assert dropdown.count() >= 1
    page.get_by_text("robot2/example", exact=True).last.wait_for()
    both = settle(page)
    save_shot(page, "two_robots")
    # one RobotModel display per robot (each on its namespace's description topic)
    page.get_by_text("RobotModel", exact=True).filter(visible=True).first.click()
    page.get_by_text("RobotModel (2)", exact=True).filter(visible=True).first.click()
    for k in (0, 1):
        row = gui_row(page, "Visual Enabled").nth(k)
        flip_checkbox(page, row.locator("input[type=checkbox]").first, f"Visual Enabled ({k + 1})")
    # robot1 at the fixed frame (centre), robot2 beside it (to the left): both are drawn.
    half = both.shape[1] // 2

    def both_hidden() -> bool:
        hidden = settle(page, 5)
        halves = ((both[:, :half], hidden[:, :half]), (both[:, half:], hidden[:, half:]))
        return all(changed_fraction(a, b) > 0.002 for a, b in halves)

    wait_for(both_hidden, what="each half of the scene to lose its robot")


def test_large_robot_with_meshes(viewer: Callable[..., ViewerProcess], page: Any) -> None:
    share = example_robot_data_dir().parents[1]
    urdf = example_robot_data_dir() / "talos_data/robots/talos_full_v2.urdf"
    view = viewer(urdf, "--package", f"example-robot-data={share / 'example-robot-data'}")
    open_viewer(page, view.url)
    wait_for(
        lambda: page.locator("text=loading").count() == 0 and page.get_by_text("OK").count(),
        timeout_s=60,
        what="every mesh to load",
    )
    drawn = settle(page)
    save_shot(page, "talos")
    toggle_checkbox(page, "Visual Enabled")
    changed_view(page, drawn, 0.01, what="talos's visuals hidden")


def test_bus_mode_draws_joint_states_from_another_process(
    viewer: Callable[..., ViewerProcess], page: Any, tmp_path: Path
) -> None:
    import subprocess

    domain = domain_id(2)
    path = write_arm(tmp_path)
    command = [*ROBOMODEL, "publish-state", str(path)]
    publisher = subprocess.Popen(
        [*command, "--bus", "zenoh", "--domain-id", domain, "--rate", "20", "--delta", "0.05"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        view = viewer(path, "--bus", "zenoh", "--domain-id", domain, "--joint-states", "external")
        open_viewer(page, view.url)
        page.get_by_text("joint states come from the bus").wait_for()
        assert page.locator("label:text-is('joint1')").count() == 0  # no sliders
        first = settle(page, 1)
        wait_for(
            lambda: changed_fraction(first, settle(page, 1)) > 0.002,
            what="the arm to move with the other process's /joint_states",
        )
        save_shot(page, "arm_external_joint_states")
    finally:
        publisher.terminate()
        publisher.wait(timeout=scaled(10))


MIMIC_AND_FLOATING = """
  <link name="link2">
    <visual><origin xyz="0 0 0.2"/><geometry><box size="0.1 0.1 0.4"/></geometry></visual>
  </link>
  <joint name="joint2" type="revolute">
    <parent link="link1"/><child link="link2"/><origin xyz="0 0.3 1.0"/><axis xyz="1 0 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/><mimic joint="joint1" multiplier="-1"/>
  </joint>
  <link name="ball">
    <visual><geometry><sphere radius="0.15"/></geometry>
      <material name="green"><color rgba="0.1 0.8 0.1 1"/></material></visual>
  </link>
  <joint name="ball_joint" type="floating">
    <parent link="base_link"/><child link="ball"/><origin xyz="0 -0.6 0.2"/>
  </joint>
"""


def test_display_options_mimic_and_floating_controls(
    viewer: Callable[..., ViewerProcess], page: Any, tmp_path: Path
) -> None:
    view = viewer(write_arm(tmp_path, extra=MIMIC_AND_FLOATING))
    open_viewer(page, view.url)
    page.get_by_text("mimics").wait_for()
    assert page.locator("label:text-is('joint2')").count() == 0  # a mimic has no slider
    start = settle(page)
    # The floating joint has pose inputs; moving it moves the ball.
    # viser breaks labels after "_" with <wbr>; the label's "for" is the first input's id.
    for_id = page.locator("label", has_text="ball_joint xyz").get_attribute("for")
    x_box = page.locator(f"[id='{for_id}']")
    x_box.fill("0.8")
    x_box.press("Tab")
    moved = changed_view(page, start, 0.001, what="the ball moved")
    save_shot(page, "arm_floating_moved")
    # Collision geometry appears; Alpha fades everything.
    toggle_checkbox(page, "Collision Enabled")
    changed_view(page, moved, 0.001, what="the collision geometry drawn")
    toggle_checkbox(page, "Collision Enabled")
    alpha = gui_row(page, "Alpha").locator("input:not([type=hidden]):visible").first  # RobotModel's
    alpha.fill("0.2")
    alpha.press("Enter")
    changed_view(page, moved, what="the robot faded")
    save_shot(page, "arm_alpha_0.2")
    # Names of the TF frames, and another Fixed Frame: the drawing moves with it.
    alpha.fill("1")
    alpha.press("Enter")
    no_names = settle(page)
    toggle_checkbox(page, "Show Names", "TF")  # labels are drawn in the 3D view (not page text)
    before = changed_view(page, no_names, 0.0005, what="the frames' names drawn")
    save_shot(page, "arm_names")
    page.locator("input[value='base_link']:not([type=hidden])").click()
    page.get_by_role("option", name="ball", exact=True).click()
    changed_view(page, before, what="the drawing moved with the fixed frame")
    save_shot(page, "arm_fixed_frame_ball")


def test_control_run_topic_pub_moves_rrbot_in_the_viewer(page: Any) -> None:
    """The seed's topic pub moves rrbot's joint1 in the viewer."""
    import subprocess
    import sys

    domain = domain_id(40)
    control = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "robomodel.cli.main",
            "control",
            "run",
            str(EXAMPLES / "rrbot_description" / "urdf" / "rrbot.xacro"),
            "--controllers",
            str(EXAMPLES / "rrbot_description" / "config" / "rrbot_control.yaml"),
            "--domain-id",
            domain,
            "--port",
            "0",
            "--no-browser",
            "--duration",
            str(scaled(90)),  # ended by the test; a bound if it is not
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        assert control.stderr is not None
        url = None
        for _ in range(20):
            line = control.stderr.readline()
            if "viewer at" in line:
                url = line.rsplit(" ", 1)[1].strip()
                break
        assert url, "control run did not start its viewer"
        open_viewer(page, url)
        before = settle(page)
        pub = subprocess.run(
            [
                sys.executable,
                "-m",
                "robomodel.cli.main",
                "topic",
                "pub",
                "/joint1_position_controller/command",
                "std_msgs/msg/Float64",
                "data: 1.5",
                "--times",
                "5",
                "--rate",
                "2",
                "--domain-id",
                domain,
            ],
            capture_output=True,
            text=True,
            timeout=scaled(30),
        )
        assert pub.returncode == 0, pub.stderr

        def moved() -> Any:
            image = settle(page)
            changed = changed_fraction(before, image)  # settle() crops already
            return (image,) if changed > 0.002 else None  # a tuple: wait_for tests truthiness

        (after,) = wait_for(moved, timeout_s=60, what="rrbot to move in the page")
        save_shot(page, "rrbot_joint1_1.5")
        # rrbot is small in the default view: a quarter turn of joint1 changes ~0.5 % of the
        # scene; a page that does not move changes none.
        assert changed_fraction(before, after) > 0.002
    finally:
        control.terminate()
        control.wait(timeout=scaled(15))
