"""Every public name of the kinematics and tf packages resolves."""

from __future__ import annotations

import importlib

import pytest

import robomodel

MODULES = [
    "robomodel.kinematics",
    "robomodel.kinematics.se3",
    "robomodel.kinematics.ik",
    "robomodel.kinematics.ur",
    "robomodel.kinematics.yaml_model",
    "robomodel.tf",
]


@pytest.mark.parametrize("module_name", MODULES)
def test_all_names_resolve(module_name: str) -> None:
    module = importlib.import_module(module_name)
    for name in module.__all__:
        assert getattr(module, name) is not None, name


def test_kinematics_is_exported() -> None:
    assert "Kinematics" in robomodel.__all__
    kin = robomodel.Kinematics(robomodel.load('<robot name="r"><link name="a"/></robot>'))
    assert kin.link_names == ("a",) and kin.n_q == 0
    assert kin.fk([]).shape == (1, 4, 4)
