"""The tf2-style buffer, with scenarios from tf2's own tests (simple_tf2_core.cpp, cache tests)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robomodel.kinematics.se3 import quat_xyzw_from_rpy
from robomodel.tf import (
    BackwardExtrapolationError,
    BufferCore,
    ConnectivityError,
    ForwardExtrapolationError,
    InvalidArgumentError,
    LookupError,
    NoDataForExtrapolationError,
    TFWarning,
    TransformStamped,
)

S = 1_000_000_000


def _tf(
    parent: str, child: str, x: float = 0.0, yaw: float = 0.0, t_s: float = 0.0
) -> TransformStamped:
    q = quat_xyzw_from_rpy([0.0, 0.0, yaw])
    return TransformStamped(parent, child, (x, 0.0, 0.0), tuple(float(v) for v in q), int(t_s * S))  # type: ignore[arg-type]


def test_lookup_nothing_exists() -> None:
    buf = BufferCore()
    with pytest.raises(
        LookupError, match=r'^"a" passed to lookupTransform argument target_frame does not exist. $'
    ):
        buf.lookup_transform("a", "b")
    assert not buf.can_transform("a", "b")
    # source == target short-circuits to identity, even for unknown frames (tf2).
    assert buf.lookup_transform("x", "x").translation_m == (0.0, 0.0, 0.0)


def test_lookup_one_exists() -> None:
    buf = BufferCore()
    assert buf.set_transform(_tf("foo", "bar", 1.0, t_s=1.0), "me")
    with pytest.raises(
        LookupError, match='"bar_none" passed to lookupTransform argument source_frame'
    ):
        buf.lookup_transform("foo", "bar_none")


def test_backward_forward_and_no_data() -> None:
    buf = BufferCore()
    buf.set_transform(_tf("foo", "bar", 1.0, t_s=2.0), "me")
    with pytest.raises(
        NoDataForExtrapolationError,
        match=r"^Lookup would require extrapolation at time 4.000000, but only time 2.000000 is in the buffer, when looking up transform from frame \[bar\] to frame \[foo\]$",
    ):
        buf.lookup_transform("foo", "bar", 4 * S)
    buf.set_transform(_tf("foo", "bar", 2.0, t_s=3.0), "me")
    with pytest.raises(
        ForwardExtrapolationError,
        match=r"into the future.  Requested time 4.000000 but the latest data is at time 3.000000",
    ):
        buf.lookup_transform("foo", "bar", 4 * S)
    with pytest.raises(
        BackwardExtrapolationError,
        match=r"into the past.  Requested time 1.000000 but the earliest data is at time 2.000000",
    ):
        buf.lookup_transform("foo", "bar", 1 * S)


def test_interpolation_linear_and_slerp() -> None:
    buf = BufferCore()
    buf.set_transform(_tf("w", "a", 0.0, yaw=0.0, t_s=1.0), "me")
    buf.set_transform(_tf("w", "a", 2.0, yaw=1.0, t_s=2.0), "me")
    t = buf.lookup_transform("w", "a", int(1.25 * S))
    assert t.translation_m[0] == pytest.approx(0.5)
    np.testing.assert_allclose(t.rotation_xyzw, quat_xyzw_from_rpy([0, 0, 0.25]), atol=1e-12)
    assert t.stamp_ns == int(1.25 * S)
    latest = buf.lookup_transform("w", "a")
    assert latest.stamp_ns == 2 * S and latest.translation_m[0] == pytest.approx(2.0)


def test_latest_common_time_and_composition() -> None:
    buf = BufferCore()
    buf.set_transform(_tf("map", "odom", 1.0, t_s=0.0), "s", is_static=True)
    buf.set_transform(_tf("odom", "base", 1.0, yaw=math.pi / 2, t_s=5.0), "d")
    buf.set_transform(_tf("odom", "base", 2.0, yaw=math.pi / 2, t_s=6.0), "d")
    buf.set_transform(_tf("base", "arm", 1.0, t_s=5.5), "d")
    # latest common time = min(6.0, 5.5): statics never limit it.
    t = buf.lookup_transform("map", "arm")
    assert t.stamp_ns == int(5.5 * S)
    np.testing.assert_allclose(t.translation_m, [1.0 + 1.5, 1.0, 0.0], atol=1e-12)
    back = buf.lookup_transform("arm", "map")
    np.testing.assert_allclose(back.matrix() @ t.matrix(), np.eye(4), atol=1e-12)
    # Siblings through their common parent.
    buf.set_transform(_tf("base", "cam", 0.5, t_s=5.5), "d")
    np.testing.assert_allclose(
        buf.lookup_transform("cam", "arm").translation_m, [0.5, 0, 0], atol=1e-12
    )


def test_connectivity_error_wording() -> None:
    buf = BufferCore()
    buf.set_transform(_tf("a", "b"), "x", is_static=True)
    buf.set_transform(_tf("c", "d"), "x", is_static=True)
    with pytest.raises(ConnectivityError) as info:
        buf.lookup_transform("a", "d")
    assert str(info.value) == (
        "Could not find a connection between 'a' and 'd' because they are not part of the same "
        "tree.Tf has two or more unconnected trees."
    )


def test_static_survives_clear_and_answers_any_time() -> None:
    buf = BufferCore()
    buf.set_transform(_tf("a", "b", 3.0), "x", is_static=True)
    buf.clear()
    t = buf.lookup_transform("a", "b", 1234 * S)
    assert t.translation_m[0] == 3.0 and t.stamp_ns == 1234 * S


def test_cache_time_prunes_and_refuses_old_data() -> None:
    buf = BufferCore()
    buf.set_transform(_tf("a", "b", 1.0, t_s=1.0), "x")
    buf.set_transform(_tf("a", "b", 2.0, t_s=20.0), "x")
    with pytest.raises(NoDataForExtrapolationError):  # t=1 was pruned (more than 10 s old)
        buf.lookup_transform("a", "b", 1 * S)
    with pytest.warns(TFWarning, match="TF_OLD_DATA"):
        assert not buf.set_transform(_tf("a", "b", 3.0, t_s=5.0), "x")


def test_rejected_inputs_warn_with_tf2_codes() -> None:
    buf = BufferCore()
    with pytest.warns(TFWarning, match="TF_SELF_TRANSFORM"):
        assert not buf.set_transform(_tf("a", "a"), "x")
    with pytest.warns(TFWarning, match="TF_NO_FRAME_ID"):
        assert not buf.set_transform(_tf("", "a"), "x")
    with pytest.warns(TFWarning, match="TF_NAN_INPUT"):
        assert not buf.set_transform(TransformStamped("a", "b", (math.nan, 0, 0)), "x")
    with pytest.warns(TFWarning, match="TF_DENORMALIZED_QUATERNION"):
        assert not buf.set_transform(TransformStamped("a", "b", rotation_xyzw=(0, 0, 0, 2)), "x")
    # A leading slash is stripped on insert but refused in lookups.
    assert buf.set_transform(_tf("/a", "/b"), "x")
    assert buf.can_transform("a", "b")
    with pytest.raises(InvalidArgumentError, match="cannot start with a '/'"):
        buf.lookup_transform("/a", "b")
    with pytest.raises(InvalidArgumentError, match="cannot be empty"):
        buf.lookup_transform("", "b")


def test_frames_as_string_and_yaml() -> None:
    buf = BufferCore()
    buf.set_transform(_tf("base", "arm"), "rsp", is_static=True)
    buf.set_transform(_tf("arm", "hand", t_s=1.0), "rsp")
    buf.set_transform(_tf("arm", "hand", t_s=3.0), "rsp")
    assert buf.all_frames_as_string() == (
        "Frame arm exists with parent base.\nFrame hand exists with parent arm.\n"
    )
    assert buf.all_frames_as_yaml() == (
        "arm: \n  parent: 'base'\n  broadcaster: 'rsp'\n  rate: 10000.000\n"
        "  most_recent_transform: 0.000000\n  oldest_transform: 0.000000\n  buffer_length: 0.000\n"
        "hand: \n  parent: 'arm'\n  broadcaster: 'rsp'\n  rate: 1.000\n"
        "  most_recent_transform: 3.000000\n  oldest_transform: 1.000000\n  buffer_length: 2.000\n"
    )
    assert BufferCore().all_frames_as_yaml() == "[]"


@pytest.mark.parametrize("static", [False, True])
def test_one_hop_lookup_is_the_general_walk(static: bool) -> None:
    """Parent<-child at time 0 answers from the child's newest sample, and gives
    exactly what the general walk gives (also when the parent's own data would extrapolate)."""
    buf = BufferCore()
    buf.set_transform(_tf("world", "base", x=0.5, t_s=1.0), "a")
    buf.set_transform(_tf("world", "base", x=0.7, t_s=3.0), "a")  # base is newer than arm
    for k, t_s in enumerate((1.0, 1.5, 2.0)):
        buf.set_transform(_tf("base", "arm", x=0.1 * k, yaw=0.3 * k, t_s=t_s), "a", static)
    expected_pose, expected_stamp = buf._walk(
        "base", "arm", buf.latest_common_time_ns("base", "arm")
    )
    result = buf.lookup_transform("base", "arm")
    assert (result.translation_m, result.rotation_xyzw) == expected_pose
    assert result.stamp_ns == expected_stamp == (0 if static else 2 * S)
    assert result.translation_m == pytest.approx((0.2, 0.0, 0.0))
    # An unknown source still fails with tf2's message; frames keep their first-seen order.
    with pytest.raises(LookupError, match="Did you mean 'arm'"):
        buf.lookup_transform("base", "armm")
    assert buf.frames == ("base", "world", "arm")


def test_frame_membership_scales_to_many_frames() -> None:
    """A 2,000-frame chain: every one-hop lookup works and the frames stay in order."""
    buf = BufferCore()
    for i in range(2000):
        buf.set_transform(_tf(f"l{i}", f"l{i + 1}", x=1.0, t_s=1.0), "a")
    assert buf.frames[:3] == ("l1", "l0", "l2")
    assert len(buf.frames) == 2001
    assert all(
        buf.lookup_transform(f"l{i}", f"l{i + 1}").translation_m == (1.0, 0.0, 0.0)
        for i in range(2000)
    )
    # tf2 walks at most 1,000 hops (MAX_GRAPH_DEPTH).
    assert buf.lookup_transform("l0", "l900").translation_m == pytest.approx((900.0, 0.0, 0.0))
