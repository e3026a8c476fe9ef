"""The packages that re-export their names lazily (:func:`robomodel._lazy.lazy_exports`): every
name of ``__all__`` resolves, and a lazily served one is the object of the module that
``_MODULE_OF`` names (a wrong module or a misspelt name there fails only when the name is
first used, which no static check sees)."""

from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

from tests.conftest import ROOT

SRC = ROOT / "src"


def _lazy_packages() -> list[str]:
    return sorted(
        ".".join(init.parent.relative_to(SRC).parts)
        for init in SRC.glob("robomodel/**/__init__.py")
        if "lazy_exports(__name__" in init.read_text()
    )


def test_the_lazy_packages_are_found() -> None:
    assert {"robomodel", "robomodel.control", "robomodel.launch.ros1"} <= set(_lazy_packages())


@pytest.mark.parametrize("name", _lazy_packages())
def test_every_exported_name_resolves_to_its_defining_module_s_object(name: str) -> None:
    package = importlib.import_module(name)
    module_of: dict[str, str] = package._MODULE_OF
    assert set(module_of) <= set(package.__all__), sorted(set(module_of) - set(package.__all__))
    for export in package.__all__:
        value = getattr(package, export)
        if export in module_of:
            defining = importlib.import_module(module_of[export])
            assert value is getattr(defining, export), f"{name}.{export}"
    assert set(package.__all__) <= set(dir(package))


@pytest.mark.process
@pytest.mark.parametrize("name", _lazy_packages())
def test_an_export_stays_after_its_module_was_loaded_directly(name: str) -> None:
    """In a fresh interpreter, every defining module loaded first (as ``robomodel.load`` loads
    ``robomodel.description.validate``), then each export taken from the package: loading a
    submodule sets the package's attribute of its name, which hid the description layer's
    ``validate`` function behind its module."""
    probe = (
        "import importlib, sys\n"
        f"package = importlib.import_module({name!r})\n"
        "for module in sorted(set(package._MODULE_OF.values())):\n"
        "    importlib.import_module(module)\n"
        "for export, module in sorted(package._MODULE_OF.items()):\n"
        "    if getattr(package, export) is not getattr(sys.modules[module], export):\n"
        "        print(export)\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True)
    assert (out.returncode, out.stdout) == (0, ""), out.stdout + out.stderr


@pytest.mark.process
def test_the_reference_snippet_s_validate_is_the_function_after_a_load() -> None:
    """docs/reference/commands.md loads a robot, then imports ``validate`` from the package."""
    probe = (
        "import robomodel\n"
        "robot = robomodel.load('examples/two_link_arm/urdf/two_link_arm.urdf')\n"
        "from robomodel.description import validate\n"
        "print(type(validate).__name__, type(validate(robot)).__name__)\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, cwd=ROOT)
    assert out.stdout.split() == ["function", "list"], out.stdout + out.stderr
