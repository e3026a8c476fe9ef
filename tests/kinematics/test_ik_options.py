"""IK options: one dataclass, one set of defaults, the same call through options= or keywords."""

from __future__ import annotations

import dataclasses
import typing

import numpy as np
import pytest

from robomodel.kinematics import IKOptions, Kinematics, KinematicsError
from robomodel.kinematics._ik_options import IKOptionOverrides


def _unreachable() -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = [5.0, 0.0, 0.0]  # far beyond the UR5's ~0.95 m reach
    return T


def test_keywords_are_the_option_fields() -> None:
    fields = {f.name: f.type for f in dataclasses.fields(IKOptions)}
    assert set(typing.get_type_hints(IKOptionOverrides)) == set(fields)


def test_options_and_keywords_give_the_same_result(ur5: Kinematics) -> None:
    T = ur5.fk_link(ur5.random_q(seed=3), "tool0")
    by_keywords = ur5.ik(T, "tool0", position_only=True, tol_m=1e-4, rng=5)
    by_options = ur5.ik(T, "tool0", options=IKOptions(position_only=True, tol_m=1e-4), rng=5)
    np.testing.assert_array_equal(by_keywords.q, by_options.q)
    assert by_keywords.iterations == by_options.iterations
    # a keyword overrides the options it is given with
    overridden = ur5.ik(T, "tool0", options=IKOptions(position_only=True), tol_m=1e-4, rng=5)
    np.testing.assert_array_equal(overridden.q, by_options.q)


def test_one_default_budget_for_ik_and_ik_batch(ur5: Kinematics) -> None:
    budget = IKOptions().max_iterations
    assert budget == 3000
    single = ur5.ik(_unreachable(), "tool0", restarts=10_000, rng=0)
    assert not single.success and single.iterations == budget
    batch = ur5.ik_batch(_unreachable()[None], "tool0", rng=0)
    assert not batch.success[0] and batch.iterations[0] == budget
    small = ur5.ik_batch(_unreachable()[None], "tool0", options=IKOptions(max_iterations=7))
    assert small.iterations[0] == 7


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"max_iterations": 0}, "max_iterations must be at least 1"),
        ({"tol_m": -1.0}, "tol_m must be a finite number >= 0"),
        ({"tol_rad": float("nan")}, "tol_rad must be a finite number >= 0"),
        ({"restarts": -1}, "restarts must be 0 or more"),
        ({"max_time_s": 0.0}, "max_time_s must be None or > 0"),
    ],
)
def test_invalid_options_name_the_option(changes: dict[str, float], message: str) -> None:
    with pytest.raises(KinematicsError, match=message):
        IKOptions(**changes)  # type: ignore[arg-type]


def test_unknown_keyword_lists_the_options(ur5: Kinematics) -> None:
    with pytest.raises(KinematicsError, match=r"unknown IK option\(s\) max_iter; options are: "):
        ur5.ik(np.eye(4), "tool0", max_iter=5)  # type: ignore[call-arg]


def test_batch_refuses_a_time_limit(ur5: Kinematics) -> None:
    with pytest.raises(KinematicsError, match="ik_batch has no time limit"):
        ur5.ik_batch(np.eye(4)[None], "tool0", max_time_s=1.0)
