"""The import finder in process: what a failed import of another name costs it."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from robomodel.clientlibs import finder
from tests.timing import scaled


def test_an_unknown_name_without_rosbags_installed_is_not_found_without_recursion(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """pip's isolated build environments have robomodel's finder (the .pth) but no rosbags:
    looking for rosbags must not ask the finder again."""
    for name in [n for n in sys.modules if n == "rosbags" or n.startswith("rosbags.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setattr(sys, "path", [])
    monkeypatch.setattr(finder, "_store_texts", [])
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    monkeypatch.chdir("/")
    assert finder.ClientLibraryFinder().find_spec("no_such_module_here", None) is None
    assert finder._store_texts == []


def test_a_name_found_to_be_no_interface_package_is_looked_for_once_per_place(
    monkeypatch: pytest.MonkeyPatch, tmp_path: object
) -> None:
    """A library that tries an optional import for every call (viser's ``import cv2`` for
    every image) pays the file checks and the close-name search once, until the places
    packages are looked for change or ``importlib.invalidate_caches()`` is called."""
    import importlib

    looks: list[str] = []
    real_may_be, real_close = finder._may_be_interface_package, finder._close_names
    monkeypatch.setattr(
        finder, "_may_be_interface_package", lambda p: looks.append(p) or real_may_be(p)
    )
    monkeypatch.setattr(
        finder, "_close_names", lambda p: looks.append(f"close {p}") or real_close(p)
    )
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    monkeypatch.setattr(finder, "_misses", {})
    found = finder.ClientLibraryFinder()
    for _ in range(3):
        assert found.find_spec("not_a_package_xyz", None) is None
    assert looks == ["not_a_package_xyz", "close not_a_package_xyz"]
    monkeypatch.chdir(str(tmp_path))  # another working folder: another workspace's src/
    assert found.find_spec("not_a_package_xyz", None) is None
    assert len(looks) == 4
    importlib.invalidate_caches()  # asks every meta path finder, this one included
    sys.meta_path.append(found)
    try:
        importlib.invalidate_caches()
    finally:
        sys.meta_path.remove(found)
    assert found.find_spec("not_a_package_xyz", None) is None
    assert len(looks) == 6


def test_a_name_that_library_code_misses_is_not_searched_for_close_names(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The standard library and installed packages try optional imports (copy.py's
    ``from org.python.core import ...``, in nearly every process): such a miss is no typo of
    the user's and costs no search for close names; the same import in a user's file names
    the close package."""
    searched: list[str] = []
    real_close = finder._close_names
    monkeypatch.setattr(finder, "_close_names", lambda p: searched.append(p) or real_close(p))
    monkeypatch.setattr(finder, "_misses", {})
    monkeypatch.setattr(sys, "meta_path", [*sys.meta_path, finder.ClientLibraryFinder()])

    def import_in(folder: str) -> str:
        code = compile("import std_msg", os.path.join(folder, "optional_imports.py"), "exec")
        with pytest.raises(ModuleNotFoundError) as failed:
            exec(code, {})
        return str(failed.value)

    library = os.path.join(sys.base_prefix, "lib", f"python{sys.version_info[0]}")
    assert import_in(library) == "No module named 'std_msg'"
    assert searched == []
    assert "did you mean std_msgs?" in import_in(os.path.join(os.sep, "home", "me", "ws"))
    assert searched == ["std_msg"]


def test_a_typo_is_still_named_the_second_time() -> None:
    found = finder.ClientLibraryFinder()
    for _ in range(2):
        with pytest.raises(ModuleNotFoundError, match="std_msgs"):
            found.find_spec("std_msg", None)


def test_a_library_name_of_an_interface_package_says_what_robomodel_serves() -> None:
    """``dynamic_reconfigure`` is an interface package (its .msg files) and, in ROS, a Python
    library: its ``client`` is not offered, and the error says so at the name."""
    import importlib

    package = importlib.import_module("dynamic_reconfigure")
    assert (
        importlib.import_module("dynamic_reconfigure.msg").Config.__typename__
        == "dynamic_reconfigure/msg/Config"
    )
    with pytest.raises(
        AttributeError, match="robomodel serves the dynamic_reconfigure interface package's"
    ):
        package.client  # noqa: B018
    assert not hasattr(package, "__wrapped__")


def test_actionlib_is_robomodels_library_and_its_interface_package() -> None:
    """``actionlib`` is robomodel's library (SimpleActionServer...) and still serves the
    actionlib interface package's messages as ``actionlib.msg``."""
    import importlib

    actionlib = importlib.import_module("actionlib")
    assert actionlib.__name__ == "robomodel.clientlibs.actionlib"
    assert actionlib.SimpleActionServer.__module__.endswith("simple_action_server")
    message = importlib.import_module("actionlib.msg")
    assert message.TestAction.__typename__ == "actionlib/msg/TestAction"
    assert actionlib.msg is message
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("actionlib.no_such_module")


def test_robomodels_own_types_are_known_without_rosbags(monkeypatch: pytest.MonkeyPatch) -> None:
    """The ``bus`` and ``sim`` extras bring no rosbags: the interface modules still list
    robomodel's own types (``from std_msgs.msg import String`` in a venv of the wheel), and
    leave out only the names of rosbags' stores."""
    import functools

    from robomodel.clientlibs import interfaces
    from robomodel.runtime.msg import _resolver

    for name in [n for n in sys.modules if n == "rosbags" or n.startswith("rosbags.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "rosbags", None)  # `import rosbags...` raises ImportError
    monkeypatch.setattr(_resolver, "_store", functools.cache(_resolver._store.__wrapped__))
    names = interfaces._type_names_of.__wrapped__(-1)
    assert {"std_msgs/msg/String", "sensor_msgs/msg/JointState"} <= names
    # in rosbags' Noetic store only: known with rosbags, not without
    assert "actionlib/msg/TestGoal" not in _resolver.definition_names()
    monkeypatch.undo()
    assert "actionlib/msg/TestGoal" in _resolver.definition_names()


def test_a_look_up_while_the_resolver_is_partly_loaded_does_not_fail(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The resolver's own imports reach the finder while its module has none of its names."""
    import types

    monkeypatch.setitem(
        sys.modules, "robomodel.runtime.msg._resolver", types.ModuleType("partly loaded")
    )
    monkeypatch.setattr(finder, "_misses", {})
    assert finder.ClientLibraryFinder().find_spec("nt_or_another_platform_module", None) is None


def _gadget_msgs(src: Path) -> None:
    """An interface package of one message, ``gadget_msgs/msg/Gadget``, under ``src``."""
    package = src / "gadget_msgs"
    (package / "msg").mkdir(parents=True)
    (package / "msg" / "Gadget.msg").write_text("int32 size\n")
    (package / "package.xml").write_text(
        "<package format='2'><name>gadget_msgs</name><version>0.0.1</version>"
        "<description>d</description><maintainer email='a@b.c'>a</maintainer>"
        "<license>BSD</license></package>"
    )


def test_a_failed_import_with_a_package_path_crawls_it_and_loads_no_type_store(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """With ``ROS_PACKAGE_PATH`` set (every ROS user's shell), a failed import of a name that
    no package has is answered from the package path's crawl, not from the type stores; an
    interface package on that path is found."""
    from robomodel.clientlibs import interfaces

    _gadget_msgs(tmp_path / "src")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "src"))
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")  # not the workspace: the package path only
    monkeypatch.setattr(finder, "_misses", {})
    monkeypatch.setattr(finder, "_interface_packages", {})
    asked: list[str] = []
    monkeypatch.setattr(interfaces, "package_names", lambda: asked.append("stores") or {})
    found = finder.ClientLibraryFinder()
    for name in ("org", "msvcrt", "winreg", "not_a_package_xyz"):
        assert found.find_spec(name, None) is None
    assert asked == []
    assert finder._package_path_interfaces() == {"gadget_msgs"}
    assert finder._may_be_interface_package("gadget_msgs")
    # a typo of a package on the path is still named, with the package meant
    with pytest.raises(ModuleNotFoundError, match="did you mean gadget_msgs"):
        found.find_spec("gadget_msg", None)
    assert asked == []


def test_the_standard_library_s_optional_imports_do_not_crawl_the_package_path(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """copy.py's ``from org.python.core import PyStringMap`` fails in every Python process: a
    name written in the standard library's own import statements is no interface package, and
    the package path (``/usr/share`` on Debian's ROS) is not crawled for it. A name that the
    standard library imports as data (``importlib.import_module(name)`` in its code, as runpy
    and multiprocessing do) is still looked for on the package path."""
    _gadget_msgs(tmp_path / "src")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "src"))
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(finder, "_misses", {})
    monkeypatch.setattr(finder, "_interface_packages", {})
    crawled: list[str | None] = []
    real_crawl = finder._crawl_package_path
    monkeypatch.setattr(
        finder,
        "_crawl_package_path",
        lambda *paths: crawled.append(paths[1]) or real_crawl(*paths),
    )
    monkeypatch.setattr(sys, "meta_path", [*sys.meta_path, finder.ClientLibraryFinder()])
    monkeypatch.delitem(sys.modules, "gadget_msgs", raising=False)
    monkeypatch.delitem(sys.modules, "gadget_msgs.msg", raising=False)
    standard_library = os.path.dirname(os.__file__)

    def run_in(folder: str, source: str) -> dict[str, object]:
        scope: dict[str, object] = {}
        exec(compile(source, os.path.join(folder, "lib_module.py"), "exec"), scope)
        return scope

    optional = "try:\n    from org.python.core import PyStringMap\nexcept ImportError:\n    pass\n"
    run_in(standard_library, optional)
    assert crawled == []
    as_data = "import importlib\nGadget = importlib.import_module(NAME).Gadget\n"
    scope = run_in(standard_library, as_data.replace("NAME", repr("gadget_msgs.msg")))
    assert crawled and set(crawled) == {str(tmp_path / "src")}
    assert getattr(scope["Gadget"], "__typename__", None) == "gadget_msgs/msg/Gadget"
    # the same optional import in a user's program is looked for on the (crawled) path
    monkeypatch.setattr(finder, "_misses", {})
    monkeypatch.setattr(finder, "_interface_packages", {})
    crawled.clear()
    run_in(str(tmp_path), optional)
    assert crawled == [str(tmp_path / "src")]


def test_a_missing_module_of_a_package_loaded_from_a_file_does_not_crawl_the_package_path(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    """numpy's ``from . import _distributor_init_local`` fails at every numpy import: a module
    of a package that Python loaded from a file is that package's business (no crawl of the
    package path), while one of robomodel's interface packages says which modules it has."""
    import importlib

    _gadget_msgs(tmp_path / "src")
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "src"))
    monkeypatch.setattr(finder, "_misses", {})
    monkeypatch.setattr(finder, "_interface_packages", {})
    crawled: list[object] = []
    real_crawl = finder._crawl_package_path
    monkeypatch.setattr(
        finder, "_crawl_package_path", lambda *paths: crawled.append(paths) or real_crawl(*paths)
    )
    monkeypatch.setattr(sys, "meta_path", [*sys.meta_path, finder.ClientLibraryFinder()])
    for name in ("yaml._no_such_module", "numpy.linalg._no_such_module"):
        with pytest.raises(ModuleNotFoundError, match=f"^No module named '{name}'$"):
            importlib.import_module(name)
    assert crawled == []
    with pytest.raises(ModuleNotFoundError, match="std_msgs has the modules msg, srv, action"):
        importlib.import_module("std_msgs.no_such_module")


@pytest.mark.process
def test_an_extension_module_s_own_optional_import_does_not_crawl_the_package_path(
    tmp_path: Path,
) -> None:
    """lxml.etree, a compiled module, tries ``import rnc2rng`` as it initialises: no Python
    code of its own writes that import, and the package path is not crawled for it."""
    code = (
        "import sys\n"
        "from robomodel.clientlibs import finder\n"
        "asked, crawled = [], []\n"
        "real_shape, real_crawl = finder._may_be_interface_module, finder._crawl_package_path\n"
        "finder._may_be_interface_module = (\n"
        "    lambda name, top: asked.append(name) or real_shape(name, top))\n"
        "finder._crawl_package_path = lambda *paths: crawled.append(paths) or real_crawl(*paths)\n"
        "import lxml.etree\n"
        "print('rnc2rng' in asked, len(crawled))\n"
    )
    _gadget_msgs(tmp_path / "src")
    env = {**os.environ, "ROS_PACKAGE_PATH": str(tmp_path / "src")}
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, cwd=tmp_path, capture_output=True, text=True,
        timeout=scaled(60), check=False,
    )  # fmt: skip
    assert out.stdout.split() == ["True", "0"], out.stdout + out.stderr


@pytest.mark.process
def test_python_with_a_package_path_imports_copy_without_the_type_stores(tmp_path: Path) -> None:
    """A fresh Python of this environment (robomodel's .pth finder installed), with
    ``ROS_PACKAGE_PATH`` set: importing the standard library loads none of robomodel's type
    machinery, nor its package index (the crawl of the path is ``os`` alone); an interface
    package on the path still imports."""
    heavy = ("rosbags", "robomodel.runtime", "robomodel.description.packages")
    code = (
        "import copy, subprocess, mimetypes, sys\n"
        f"print(sorted(m for m in sys.modules if m.startswith({heavy!r})))\n"
        "from gadget_msgs.msg import Gadget\n"
        "print(Gadget(size=3).size)\n"
    )
    _gadget_msgs(tmp_path / "src")
    env = {**os.environ, "ROS_PACKAGE_PATH": str(tmp_path / "src")}
    env.pop("ROBOMODEL_CLIENTLIBS", None)
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, cwd="/", capture_output=True, text=True,
        timeout=scaled(60), check=False,
    )  # fmt: skip
    assert out.stdout.splitlines() == ["[]", "3"], out.stdout + out.stderr
