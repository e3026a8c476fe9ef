"""Every public name of the control packages resolves."""

from __future__ import annotations

import importlib

import pytest

MODULES = [
    "robomodel.control",
    "robomodel.control.hardware",
    "robomodel.control.controllers",
    "robomodel.control.transmissions",
    "robomodel.kinematics",
    "robomodel.runtime.msg",
]


@pytest.mark.parametrize("module_name", MODULES)
def test_all_names_resolve(module_name: str) -> None:
    module = importlib.import_module(module_name)
    for name in module.__all__:
        assert getattr(module, name) is not None, name
