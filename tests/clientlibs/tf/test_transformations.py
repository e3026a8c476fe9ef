"""tf.transformations against Debian's own ``tf/transformations.py`` (loaded from its file as
an independent reference) and robomodel's rigid-body code, on random and degenerate inputs."""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from robomodel.clientlibs.tf import transformations as tr
from robomodel.description import rigid

REFERENCE = Path("/usr/lib/python3/dist-packages/tf/transformations.py")
AXES = [f + a + b + c for f in "sr" for a in "xyz" for b in "xyz" for c in "xyz" if a != b != c]
ANGLE = st.floats(-math.pi, math.pi)


@pytest.fixture(scope="module")
def ref() -> ModuleType:
    if not REFERENCE.exists():
        pytest.fail(f"Debian's tf is missing ({REFERENCE}): tools/system-deps test installs it")
    spec = importlib.util.spec_from_file_location("debian_tf_transformations", REFERENCE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_24_conventions_are_tfs(ref: ModuleType) -> None:
    assert sorted(AXES) == sorted(ref._AXES2TUPLE)


@pytest.mark.parametrize("axes", AXES)
def test_euler_conventions_match_tf(ref: ModuleType, axes: str) -> None:
    rng = np.random.default_rng(abs(hash(axes)) % 2**32)
    angles = [rng.uniform(-math.pi, math.pi, 3) for _ in range(20)]
    angles += [np.array([0.3, b, -1.2]) for b in (0.0, math.pi / 2, -math.pi / 2, math.pi)]
    for a in angles:
        m = ref.euler_matrix(*a, axes=axes)
        np.testing.assert_allclose(tr.euler_matrix(*a, axes=axes), m, atol=1e-12)
        np.testing.assert_allclose(
            tr.quaternion_from_euler(*a, axes=axes), ref.quaternion_from_euler(*a, axes=axes),
            atol=1e-12,
        )  # fmt: skip
        np.testing.assert_allclose(
            tr.euler_from_matrix(m, axes), ref.euler_from_matrix(m, axes), atol=1e-7
        )
        back = tr.euler_matrix(*tr.euler_from_matrix(m, axes), axes=axes)
        np.testing.assert_allclose(back, m, atol=1e-9)


def test_known_values() -> None:
    # a quarter turn about z: x goes to y
    q = tr.quaternion_from_euler(0.0, 0.0, math.pi / 2)
    np.testing.assert_allclose(q, [0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)], atol=1e-15)
    np.testing.assert_allclose(tr.quaternion_matrix(q)[:3, 0], [0.0, 1.0, 0.0], atol=1e-15)
    assert tr.euler_from_quaternion([0.0, 0.0, 0.0, 1.0]) == (0.0, -0.0, 0.0)
    np.testing.assert_allclose(tr.euler_from_quaternion(q), (0.0, 0.0, math.pi / 2), atol=1e-15)
    # rotating zyx by (yaw, pitch, roll) is static xyz by (roll, pitch, yaw)
    np.testing.assert_allclose(
        tr.euler_matrix(0.3, 0.2, 0.1, "rzyx"), tr.euler_matrix(0.1, 0.2, 0.3, "sxyz")
    )
    m = tr.concatenate_matrices(
        tr.translation_matrix([1, 2, 3]), tr.rotation_matrix(math.pi, [0, 0, 1])
    )
    np.testing.assert_allclose(m @ [1, 0, 0, 1], [0, 2, 3, 1], atol=1e-15)
    np.testing.assert_allclose(tr.inverse_matrix(m) @ m, np.eye(4), atol=1e-15)
    np.testing.assert_allclose(tr.translation_from_matrix(m), [1, 2, 3])
    with pytest.raises(ValueError, match="unknown axes 'sxxy'"):
        tr.euler_matrix(0, 0, 0, "sxxy")


@given(ANGLE, ANGLE, ANGLE)
def test_rpy_matches_robomodels_rigid_body_code(roll: float, pitch: float, yaw: float) -> None:
    q = tr.quaternion_from_euler(roll, pitch, yaw)
    ours = rigid.quat_xyzw_from_rpy(roll, pitch, yaw)
    assert np.allclose(q, ours, atol=1e-12) or np.allclose(q, -np.asarray(ours), atol=1e-12)
    other = tr.quaternion_from_euler(yaw, roll, pitch)
    np.testing.assert_allclose(
        tr.quaternion_multiply(q, other), rigid.qmul_xyzw(tuple(q), tuple(other)), atol=1e-12
    )
    np.testing.assert_allclose(
        tr.quaternion_conjugate(q), rigid.conjugate_xyzw(tuple(q)), atol=1e-15
    )


def test_quaternions_and_rotations_match_tf(ref: ModuleType) -> None:
    rng = np.random.default_rng(7)
    for i in range(100):
        m = ref.random_rotation_matrix(rng.random(3))
        if i % 5 == 0:  # half turns: the trace is -1, the sign rule's other branch
            m = ref.rotation_matrix(math.pi, rng.normal(size=3))
        np.testing.assert_allclose(
            tr.quaternion_from_matrix(m), ref.quaternion_from_matrix(m), atol=1e-12
        )
        q0, q1 = ref.random_quaternion(rng.random(3)), ref.random_quaternion(rng.random(3))
        np.testing.assert_allclose(
            tr.random_quaternion(q0[:3] ** 2), ref.random_quaternion(q0[:3] ** 2)
        )
        np.testing.assert_allclose(tr.quaternion_multiply(q1, q0), ref.quaternion_multiply(q1, q0))
        np.testing.assert_allclose(tr.quaternion_matrix(q0), ref.quaternion_matrix(q0), atol=1e-15)
        np.testing.assert_allclose(tr.quaternion_inverse(q0), ref.quaternion_inverse(q0))
        f = float(rng.random())
        np.testing.assert_allclose(tr.quaternion_slerp(q0, q1, f), ref.quaternion_slerp(q0, q1, f))
        angle, axis, point = float(rng.uniform(-3, 3)), rng.normal(size=3), rng.normal(size=3)
        np.testing.assert_allclose(
            tr.quaternion_about_axis(angle, axis), ref.quaternion_about_axis(angle, axis)
        )
        r = ref.rotation_matrix(angle, axis, point)
        np.testing.assert_allclose(tr.rotation_matrix(angle, axis, point), r, atol=1e-12)
        np.testing.assert_allclose(tr.rotation_matrix(*tr.rotation_from_matrix(r)), r, atol=1e-9)
        np.testing.assert_allclose(
            tr.scale_matrix(1.5, point, axis), ref.scale_matrix(1.5, point, axis)
        )
        scale, shear = rng.uniform(0.5, 2, 3), rng.uniform(-0.5, 0.5, 3)
        angles, translate = rng.uniform(-1, 1, 3), rng.normal(size=3)
        c = ref.compose_matrix(scale, shear, angles, translate)
        np.testing.assert_allclose(
            tr.compose_matrix(scale, shear, angles, translate), c, atol=1e-12
        )
        for ours, theirs in zip(tr.decompose_matrix(c), ref.decompose_matrix(c), strict=True):
            np.testing.assert_allclose(ours, theirs, atol=1e-9)
        assert tr.is_same_transform(c, c * 2.0) and not tr.is_same_transform(c, r)


def test_what_is_not_offered_says_so() -> None:
    with pytest.raises(NotImplementedError, match=r"tf.transformations.shear_matrix\(\)"):
        tr.shear_matrix(0.1, [1, 0, 0], [0, 0, 0], [0, 0, 1])
    with pytest.raises(AttributeError, match="no attribute 'nonsense'"):
        tr.nonsense  # noqa: B018
