"""FK equals pinocchio on every example-robot-data robot and every example package."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pinocchio
import pytest

from robomodel.description import read_urdf
from robomodel.errors import InputError
from robomodel.kinematics import Kinematics, KinematicsWarning
from tests.conftest import example_robot_data_urdfs, example_urdfs
from tests.kinematics._pin import pin_link_poses

# Invalid for both robomodel and pinocchio (a xacro leftover whose <robot> has no name): the
# test asserts that both reject it instead of skipping it.
INVALID = {"ur3.urdf"}

# Its finger joints mimic 'index_q1' etc., which do not exist (the real names have a Left_/Right_
# prefix): robomodel warns and keeps them independent, as pinocchio does.
MISSING_MIMIC_SOURCE = {"alex_psyonic_hands.urdf"}

CORPUS = [*example_robot_data_urdfs(), *example_urdfs()]


def _id(path: Path) -> str:
    return f"{path.parent.parent.name}/{path.name}"


@pytest.mark.parametrize("path", CORPUS, ids=_id)
def test_fk_matches_pinocchio(path: Path) -> None:
    if path.name in INVALID:
        with pytest.raises(InputError):
            read_urdf(str(path))
        with pytest.raises(ValueError):
            pinocchio.buildModelFromUrdf(str(path))
        return
    robot = read_urdf(str(path)).robot
    if path.name in MISSING_MIMIC_SOURCE:
        with pytest.warns(KinematicsWarning, match="which does not exist"):
            kin = Kinematics(robot)
    else:
        with warnings.catch_warnings():
            warnings.simplefilter("error", KinematicsWarning)
            kin = Kinematics(robot)
    model = pinocchio.buildModelFromUrdf(str(path))
    rng = np.random.default_rng(7)
    qs = kin.random_q(4, seed=rng)
    # Values outside the limits are accepted by FK (and by pinocchio).
    qs = np.concatenate([qs, rng.uniform(-4.0, 4.0, size=(2, kin.n_q))])
    batch = kin.fk(qs)
    assert batch.shape == (len(qs), len(kin.link_names), 4, 4)
    for q, Ts_batch in zip(qs, batch, strict=True):
        expected = pin_link_poses(kin, model, q)
        np.testing.assert_allclose(kin.fk(q), expected, rtol=0, atol=1e-10)
        np.testing.assert_allclose(Ts_batch, expected, rtol=0, atol=1e-10)


def test_corpus_is_not_empty() -> None:
    assert len(CORPUS) > 60
