"""RViz's TF display ages frames (frame_info.cpp ``updateColorForAge``): normal for the first
third of Frame Timeout, fading to grey over the second, fading out over the last, then not
drawn; static transforms never age. Checked as a schedule and through the display, with a
clock the test sets."""

from __future__ import annotations

import numpy as np
import pytest

from robomodel.tf.buffer import BufferCore
from robomodel.tf.message import TransformStamped
from robomodel.viewer.displays import display_class
from robomodel.viewer.displays.tf_fade import AXES_RGBA, GREY_RGBA, HEAD_RGBA, SHAFT_RGBA, aged_rgba
from tests.viewer.fake_scene import FakeScene, fake_context

TF = display_class("rviz_default_plugins/TF")
S = 10**9  # ns per s


def test_a_frame_keeps_its_colours_for_a_third_of_the_timeout() -> None:
    rgba = aged_rgba(AXES_RGBA, [0.0, 1.0, 2.9], 9.0)
    np.testing.assert_allclose(rgba, np.broadcast_to(AXES_RGBA, (3, 3, 4)))


def test_over_the_second_third_it_fades_linearly_to_grey() -> None:
    timeout = 9.0
    # halfway through (4.5 s): half default, half grey (lerpColor with t = 0.5)
    half = aged_rgba((*AXES_RGBA, SHAFT_RGBA, HEAD_RGBA), [4.5], timeout)[0]
    expected = (np.array((*AXES_RGBA, SHAFT_RGBA, HEAD_RGBA)) + GREY_RGBA) / 2
    np.testing.assert_allclose(half, expected, atol=1e-6)
    np.testing.assert_allclose(half[0], [0.85, 0.35, 0.35, 1.0], atol=1e-6)  # x: red to grey
    quarter = aged_rgba(AXES_RGBA, [3.75], timeout)[0, 2]  # a quarter of the way: t = 0.75
    np.testing.assert_allclose(quarter, [0.175, 0.175, 0.925, 1.0], atol=1e-6)
    at_two_thirds = aged_rgba(AXES_RGBA, [6.0 - 1e-9], timeout)[0]
    np.testing.assert_allclose(at_two_thirds, np.tile(GREY_RGBA, (3, 1)), atol=1e-6)


def test_over_the_last_third_grey_fades_out_and_is_gone_at_the_timeout() -> None:
    rgba = aged_rgba(AXES_RGBA, [7.5, 9.0, 20.0], 9.0)
    np.testing.assert_allclose(rgba[..., :3], 0.7)
    np.testing.assert_allclose(rgba[:, :, 3], [[0.5] * 3, [0.0] * 3, [0.0] * 3], atol=1e-6)
    ages = np.linspace(0.0, 10.0, 101)
    alpha = aged_rgba(AXES_RGBA, ages, 9.0)[:, 0, 3]
    assert np.all(np.diff(alpha) <= 0) and alpha[0] == 1.0  # never comes back


def _instance_colors(scene: FakeScene, axis: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    node = scene.nodes[f"/displays/TF/axes/{axis}"]
    kwargs = node.kwargs
    return (np.asarray(kwargs["batched_positions"]), np.asarray(kwargs["batched_colors"]),
            np.asarray(kwargs["batched_opacities"]))  # fmt: skip


def test_the_display_draws_a_frame_half_a_timeout_old_greyed_and_one_past_it_not_at_all() -> None:
    """``moving`` is published once; ``laser`` is static below it and ages with it (RViz asks
    for the latest common time with the fixed frame); ``static`` never ages."""
    now = [1000 * S]
    scene = FakeScene()
    tf = TF("TF", fake_context(scene, clock=lambda: now[0]), {"Frame Timeout": 6.0})
    buffer = BufferCore()
    buffer.set_transform(TransformStamped("map", "static", (1.0, 0, 0)), "test", is_static=True)
    buffer.set_transform(TransformStamped("map", "moving", (0, 1.0, 0), stamp_ns=now[0]), "test")
    buffer.set_transform(TransformStamped("moving", "laser", (0, 0, 1.0)), "test", is_static=True)
    frames = ("map", "static", "moving", "laser")
    xyz = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 1, 1]])

    def show() -> None:
        tf.show_frames(frames, np.tile([1.0, 0, 0, 0], (4, 1)), xyz, np.ones(4, bool), buffer)

    show()  # "moving" published now: all as RViz draws fresh frames
    positions, colors, opacities = _instance_colors(scene, "x")
    assert colors.tolist() == [[255, 0, 0]] * 4 and opacities.tolist() == [1.0] * 4
    assert not tf.fading()
    now[0] += 3 * S  # half the timeout, nothing published since
    assert tf.fading()  # the viewer redraws though nothing moved
    show()
    positions, colors, opacities = _instance_colors(scene, "x")
    np.testing.assert_allclose(positions, xyz)
    half_grey_red = [217, 89, 89]  # (1, 0, 0) and (0.7, 0.7, 0.7), half each
    assert colors.tolist() == [[255, 0, 0], [255, 0, 0], half_grey_red, half_grey_red]
    assert _instance_colors(scene, "z")[1].tolist()[2] == [89, 89, 217]
    assert opacities.tolist() == [1.0] * 4
    arrows = scene.nodes["/displays/TF/arrows"].kwargs
    np.testing.assert_allclose(arrows["points"][:2], [[[1, 0, 0], [0, 0, 0]], [[0, 1, 0], [0, 0, 0]]])  # fmt: skip
    assert arrows["colors"][:2].tolist() == [
        [[204, 204, 77], [255, 26, 153]],  # static's: fresh
        [[191, 191, 128], [217, 102, 166]],  # moving's: greyed
    ]
    now[0] += int(1.5 * S)  # three quarters: grey, alpha (6 - 4.5) / 2
    show()
    _, colors, opacities = _instance_colors(scene, "y")
    assert colors.tolist()[2] == [179, 179, 179] and opacities[2] == pytest.approx(0.75, abs=1e-5)
    now[0] += 2 * S  # past the timeout: gone, with its arrow and its static child
    show()
    assert tf.shown == ("map", "static")
    positions, colors, _ = _instance_colors(scene, "x")
    np.testing.assert_allclose(positions, xyz[:2])
    assert len(scene.nodes["/displays/TF/arrows"].kwargs["points"]) == 1
    assert not tf.fading()  # nothing left to fade: no more redraws
    old = 1001 * S  # published again, stamped 5.5 s before the clock (a clock behind ours)
    buffer.set_transform(TransformStamped("map", "moving", (0, 1.0, 0), stamp_ns=old), "test")
    show()
    assert tf.shown == frames  # its age counts from when the stamp changed, as RViz's
    assert _instance_colors(scene, "x")[1].tolist()[2] == [255, 0, 0]


def test_a_clock_that_goes_back_starts_the_tf_display_over() -> None:
    """ROS time going back (a simulation reset, a bag played again, use_sim_time switched on)
    resets every display, as RViz's resetTime does: the TF display draws again at once, and
    a frame seen before the jump counts its age from the new clock, not from the old one."""
    from robomodel.runtime import Context
    from robomodel.viewer.displays.manager import DisplayManager

    now = [1000 * S]
    scene = FakeScene()
    buffer = BufferCore()
    context = Context()
    manager = DisplayManager(fake_context(scene, clock=lambda: now[0]), context.create_node("viewer"), buffer)  # fmt: skip
    tf = manager.add("TF", values={"Frame Timeout": 6.0})
    frames = ("map", "moving")
    xyz = np.array([[0.0, 0, 0], [0, 1, 0]])

    def show() -> None:
        manager.update()
        tf.show_frames(frames, np.tile([1.0, 0, 0, 0], (2, 1)), xyz, np.ones(2, bool), buffer)

    buffer.set_transform(TransformStamped("map", "moving", (0, 1.0, 0), stamp_ns=now[0]), "test")
    show()
    now[0] += 5 * S  # five sixths of the timeout: fading out
    show()
    assert _instance_colors(scene, "x")[1].tolist()[1] == [179, 179, 179]
    now[0] = 10 * S  # the clock went back; "moving" is not published again
    show()
    assert tf.shown == frames
    assert _instance_colors(scene, "x")[1].tolist() == [[255, 0, 0], [255, 0, 0]]  # fresh
    now[0] += 5 * S  # and it ages on the new clock (not fresh until the old one is back)
    show()
    assert _instance_colors(scene, "x")[1].tolist()[1] == [179, 179, 179]
    context.shutdown()
