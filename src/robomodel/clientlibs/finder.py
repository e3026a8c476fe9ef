"""The import finder that makes ROS's Python names importable on robomodel.

Two kinds of names:

- **client libraries**: ``rclpy``, ``rospy`` and the helper libraries are aliases of
  ``robomodel.clientlibs.<name>`` (``import rclpy.node`` is ``robomodel.clientlibs.rclpy.node``,
  one module object under both names);
- **interface packages**: ``<pkg>.msg``, ``<pkg>.srv`` and ``<pkg>.action`` of every package
  whose types robomodel knows (:mod:`.interfaces`), with no build step.

The finder is appended to ``sys.meta_path``: Python's own path finder asks first, so a real ROS
installation on ``sys.path`` (a sourced ``setup.bash``) or a real message package always wins.
One thing Python's finder would find first is not a message package: a package's source folder
on ``sys.path`` (``python3 -c`` in a workspace's ``src/``), whose ``msg/`` and ``srv/`` folders
have no ``__init__.py`` and would import as empty namespace packages. A second finder, first on
``sys.meta_path``, serves those names when the path finder finds nothing but such a folder.
"""

from __future__ import annotations

import _imp
import _thread
import importlib
import importlib.machinery
import importlib.util
import os
import sys
from types import CodeType, FrameType, ModuleType

from robomodel.clientlibs import _workspace

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing at every Python start
if TYPE_CHECKING:
    from collections.abc import Sequence
    from importlib.abc import Loader as _LoaderBase
else:
    _LoaderBase = object  # importlib.abc would import importlib.resources at every start

__all__ = ["ALIASED", "ClientLibraryFinder", "install", "installed"]

_HOME = "robomodel.clientlibs"

# Top-level names served from robomodel.clientlibs.<name>, when that sub-package exists.
ALIASED = frozenset(
    {
        "rclpy",
        "rospy",
        "genpy",
        "tf",
        "tf2_ros",
        "ament_index_python",
        "rospkg",
        "roslib",
        "rostest",
        "sensor_msgs_py",
        "actionlib",
    }
)


# The interface modules of a package (interfaces.KINDS, without importing it at every start).
_KINDS = ("msg", "srv", "action")

# Python modules of ROS 1 message packages that rospy programs import beside the messages.
HELPERS = {"sensor_msgs.point_cloud2": f"{_HOME}.rospy.point_cloud2"}


class _AliasLoader(_LoaderBase):
    """Gives the module ``target`` (imported once) under the alias being imported."""

    def __init__(self, target: str) -> None:
        self.target = target

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        if spec.submodule_search_locations is not None and not any(
            isinstance(f, _SubmoduleAliasFinder) for f in sys.meta_path
        ):
            sys.meta_path.insert(0, _SubmoduleAliasFinder())
        return importlib.import_module(self.target)

    def exec_module(self, module: ModuleType) -> None:
        """Nothing: the target module ran when it was imported under its own name."""


class _SubmoduleAliasFinder:
    """First on ``sys.meta_path`` once an aliased package is imported: ``rclpy.node`` is then
    ``robomodel.clientlibs.rclpy.node`` (one module object), never a second copy that Python's
    path finder would load from the package's folder under the alias's name (two classes of
    one name: an ``except rclpy.exceptions.X`` that misses the X robomodel raises). Only for
    an alias whose top-level module is robomodel's, so a real ROS install still wins."""

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        top, dot, _ = fullname.partition(".")
        if not dot or top not in ALIASED:
            return None
        parent = sys.modules.get(top)
        if parent is None or not getattr(parent, "__name__", "").startswith(f"{_HOME}."):
            return None
        real = f"{_HOME}.{fullname}"
        found = importlib.util.find_spec(real)
        if found is None:
            return None
        return importlib.machinery.ModuleSpec(
            fullname, _AliasLoader(real), is_package=found.submodule_search_locations is not None
        )


class _OverNamespaceFinder:
    """First on ``sys.meta_path``: ``<pkg>.msg``, ``<pkg>.srv`` and ``<pkg>.action`` of an
    interface package robomodel knows, when ``<pkg>`` imported as a namespace package (a folder
    without ``__init__.py`` on ``sys.path``, such as the package's own source folder) and
    Python's path finder finds no module of that name but a folder of ``.msg`` files. A real
    module (a ``msg/__init__.py``, a ``msg.py``) still wins."""

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        package, _, kind = fullname.rpartition(".")
        if kind not in _KINDS or not package or "." in package:
            return None
        parent = getattr(sys.modules.get(package), "__spec__", None)
        if parent is None or not _is_namespace(parent):
            return None
        found = importlib.machinery.PathFinder.find_spec(fullname, path)
        if found is not None and not _is_namespace(found):
            return None
        if not _may_be_interface_package(package):
            return None
        from robomodel.clientlibs import interfaces

        try:
            return interfaces.find_spec(fullname)
        except ModuleNotFoundError:  # not a package robomodel knows: the folder stays
            return None


def _is_namespace(spec: importlib.machinery.ModuleSpec) -> bool:
    """Whether ``spec`` is a namespace package's: folders, no file, nothing to run."""
    return spec.origin is None and spec.submodule_search_locations is not None


class ClientLibraryFinder:
    """Finds the aliased client libraries and the interface packages' message modules (a
    meta path finder and its loaders by protocol: ``importlib.abc`` would cost every Python
    start in the environment the import of ``importlib.resources``)."""

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        top = fullname.partition(".")[0]
        if top in ALIASED:
            real = f"{_HOME}.{fullname}"
            try:
                found = importlib.util.find_spec(real)
            except ModuleNotFoundError:  # the alias's parent is not a robomodel package
                return None
            if found is not None:
                return importlib.machinery.ModuleSpec(
                    fullname,
                    _AliasLoader(real),
                    is_package=found.submodule_search_locations is not None,
                )
            if fullname.count(".") != 1 or fullname.rpartition(".")[2] not in _KINDS:
                return None
            # a library that is also an interface package (actionlib): its msg module
            from robomodel.clientlibs import interfaces

            return interfaces.find_spec(fullname)
        helper = HELPERS.get(fullname)
        if helper is not None:
            return importlib.machinery.ModuleSpec(fullname, _AliasLoader(helper))
        if not _may_be_interface_module(fullname, top):
            return None
        importer = _importing_code()
        if importer is _EXTENSION_INIT:
            return None
        if importer is not None and _standard_library_names(importer, top):
            return None
        by_library = importer is not None and importer.co_filename.startswith(_LIBRARY_FOLDERS)
        key = (fullname, path is None, by_library, *_where_packages_are())
        close = _misses.get(key)
        if close is None:
            if _may_be_interface_package(top):
                from robomodel.clientlibs import interfaces

                spec = interfaces.find_spec(fullname)  # raises for a typo, with close names
                if spec is not None:
                    return spec
                close = ()
            elif fullname == top and path is None and not by_library:
                close = tuple(_close_names(top))
            else:
                close = ()
            if len(_misses) >= _MISSES_KEPT:
                _misses.clear()
            _misses[key] = close
        if close:  # a typo of an interface package's name: say so, with what was meant
            from robomodel.clientlibs import interfaces

            raise ModuleNotFoundError(interfaces.not_found(top, list(close)), name=top)
        return None

    def invalidate_caches(self) -> None:
        """``importlib.invalidate_caches()``: packages made since are looked for again."""
        _misses.clear()


# Where the standard library and installed packages are: an import they make of a name that is
# no interface package is an optional one (copy.py's ``from org.python.core import ...`` in
# every process), not a user's typo, and is not searched for close names (a few milliseconds).
_LIBRARY_FOLDERS = tuple(
    {
        os.path.join(p, "")
        for p in (sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix)
    }
)
_FROZEN_IMPORTLIB = "<frozen importlib"
_IMPORTLIB_INIT = os.path.join("importlib", "__init__.py")  # import_module's frame


def _may_be_interface_module(fullname: str, top: str) -> bool:
    """Whether ``fullname`` has the shape of a module this finder serves: ``pkg``, or
    ``pkg.msg``/``.srv``/``.action``, or another module of ``pkg`` when ``pkg`` is robomodel's
    interface package (whose error then names the modules it has). A module of a package that
    Python loaded from a file (numpy's optional ``numpy._distributor_init_local``) is that
    package's own business, and costs no crawl of the package path."""
    depth = fullname.count(".")
    if depth == 0:
        return True
    if depth > 1:
        return False
    return (
        fullname.rpartition(".")[2] in _KINDS
        or getattr(sys.modules.get(top), "__file__", None) is None
    )


def _importing_code() -> CodeType | None:
    """The code that wrote the import being looked up: a script, ``python -c``, a library's
    module (a test's, when it calls ``find_spec`` itself), past the import machinery's own
    frames (``importlib.import_module``'s included); :data:`_EXTENSION_INIT` when a compiled
    extension module imports as it initialises (lxml.etree's optional ``rnc2rng``), which has
    no Python code of its own."""
    # the import machinery's frame that called find_spec (or a test's that called it directly)
    frame: FrameType | None = sys._getframe(2)
    while frame is not None and (
        frame.f_code.co_filename.startswith(_FROZEN_IMPORTLIB)
        or frame.f_code.co_filename.endswith(_IMPORTLIB_INIT)
    ):
        # ExtensionFileLoader.exec_module: _call_with_frames_removed(_imp.exec_dynamic, module)
        if frame.f_code.co_name == "_call_with_frames_removed" and (
            frame.f_locals.get("f") is _imp.exec_dynamic
        ):
            return _EXTENSION_INIT
        frame = frame.f_back
    return frame.f_code if frame is not None else None


# The importer of an import that a compiled extension module makes as it initialises: its
# optional dependencies (lxml's rnc2rng), never a ROS interface package.
_EXTENSION_INIT = compile("", "<an extension module's initialisation>", "exec")


# The standard library's own folder (os.py's), without the installed packages that a Python
# with no venv keeps below it.
_STANDARD_LIBRARY = os.path.join(os.path.dirname(os.__file__), "")
_INSTALLED = (f"{os.sep}site-packages{os.sep}", f"{os.sep}dist-packages{os.sep}")


def _standard_library_names(importer: CodeType, top: str) -> bool:
    """Whether the standard library's own code imports ``top`` by a name written in it (the
    module names of an import statement are among its code's names): its optional imports of
    other platforms' modules (copy.py's and pickle.py's ``from org.python.core import ...``,
    platform.py's ``java.lang``), which no ROS package serves. Without this, the first of them
    in every Python process crawled the whole package path (with ``ROS_PACKAGE_PATH`` holding
    ``/usr/share``, as on Debian's ROS, 180 ms). A name the standard library imports as data
    (runpy's ``-m``, pickle's classes in multiprocessing's spawned children) is no name of its
    code and is looked for as any other."""
    file = importer.co_filename
    if not (file.startswith(_STANDARD_LIBRARY) or file.startswith("<frozen ")):
        return False
    if any(folder in file for folder in _INSTALLED):
        return False
    prefix = f"{top}."
    return any(name == top or name.startswith(prefix) for name in importer.co_names)


# Names found to be no interface package, with the close names a typo of them gets, per place
# packages are looked for: a library that tries an optional import for every call (viser's
# ``import cv2`` for every image) pays a dictionary look-up, not the file checks and the
# difflib search each time.
_misses: dict[tuple[object, ...], tuple[str, ...]] = {}
_MISSES_KEPT = 4096


def _where_packages_are() -> tuple[object, ...]:
    """What decides whether a name is an interface package, besides the name: the working
    folder (a workspace's ``src/``), the package path variables and ``--package-path``."""
    # None while the resolver is still being imported: its own imports reach this finder
    generation = getattr(sys.modules.get("robomodel.runtime.msg._resolver"), "generation", None)
    try:
        here = os.getcwd()
    except OSError:  # the working folder was removed: no workspace is there
        here = ""
    return (
        here,
        os.environ.get("ROS_PACKAGE_PATH"),
        os.environ.get("AMENT_PREFIX_PATH"),
        generation() if generation is not None else None,
    )


_MSG = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "runtime", "msg")
# Python asks for these at every start; they are never interface packages.
_STARTUP_HOOKS = frozenset({"sitecustomize", "usercustomize"})
_store_texts: list[str] = []  # stays empty when rosbags is not installed (looked for each time)


def _never_a_package(name: str) -> bool:
    """Names no interface package has: not identifiers, private, Python's start-up hooks, and
    Python's own modules of other platforms, which the standard library tries at import
    (subprocess's ``msvcrt``, mimetypes' ``winreg``): a ROS package so named would not import."""
    return (
        not name.isidentifier()
        or name.startswith("_")
        or name in _STARTUP_HOOKS
        or name in sys.stdlib_module_names
    )


def _may_be_interface_package(package: str) -> bool:
    """A quick look, with no import, whether ``package`` can be an interface package robomodel
    knows. Every failed ``import`` in the process reaches this finder: it should cost a few
    file checks, not the loading of the type stores."""
    if _never_a_package(package):
        return False
    if os.path.isfile(os.path.join(_MSG, "types", f"{package}.py")):
        return True
    if os.path.isdir(os.path.join(_MSG, "interfaces", package)):
        return True
    if package in _package_path_interfaces():
        return True
    if _in_workspace_src(package):
        return True
    needle = f"'{package}/"
    return any(needle in text for text in _rosbags_store_texts())


# The interface packages on the package path, per package path: each crawl (rospack's, by
# robomodel's package index) costs milliseconds, where interfaces.package_names() would load the
# type stores at the first failed import of every Python process (copy.py's
# ``from org.python.core import PyStringMap``).
_interface_packages: dict[tuple[object, ...], frozenset[str]] = {}
_crawl_lock = _thread.allocate_lock()  # the crawl's own imports return before it (_crawling)
_crawling = _thread._local()  # the crawl's own imports reach this finder: they find nothing


def _package_path_interfaces() -> frozenset[str]:
    """The packages with ``msg/``, ``srv/`` or ``action/`` folders on ``ROS_PACKAGE_PATH``,
    ``AMENT_PREFIX_PATH`` and ``--package-path`` (``robomodel run``/``launch``)."""
    # None while the resolver is still being imported: its own imports reach this finder
    # (pathlib's ``from nt import ...`` on POSIX, where nothing imported pathlib before)
    package_paths = getattr(
        sys.modules.get("robomodel.runtime.msg._resolver"), "package_paths", None
    )
    extra = tuple(package_paths()) if package_paths is not None else ()
    variables = (os.environ.get("ROS_PACKAGE_PATH"), os.environ.get("AMENT_PREFIX_PATH"))
    if not any(variables) and not extra:
        return frozenset()
    key = (*variables, extra)
    found = _interface_packages.get(key)
    if found is not None or getattr(_crawling, "on", False):
        return found or frozenset()
    with _crawl_lock:
        found = _interface_packages.get(key)
        if found is not None:
            return found
        _crawling.on = True
        try:
            found = frozenset(
                name
                for name, folder in _crawl_package_path(extra, *variables).items()
                if any(os.path.isdir(os.path.join(folder, k)) for k in _KINDS)
            )
        finally:
            _crawling.on = False
        if len(_interface_packages) >= 16:
            _interface_packages.clear()
        _interface_packages[key] = found
    return found


def _crawl_package_path(
    package_paths: Sequence[str | os.PathLike[str]],
    ros_package_path: str | None,
    ament_prefix_path: str | None,
) -> dict[str, str]:
    """The packages (name -> folder; the first of a name wins) of ``--package-path``,
    ``ROS_PACKAGE_PATH`` and ``AMENT_PREFIX_PATH``, found as the package index finds them
    (:mod:`robomodel.description._crawl`), without its imports."""
    from robomodel.description import _crawl

    found: dict[str, str] = {}
    for root in (*package_paths, *_crawl.split_paths(ros_package_path)):
        _crawl.scan_tree(os.path.abspath(root), found)  # keeps the first folder of a name
    for prefix in map(os.path.abspath, _crawl.split_paths(ament_prefix_path)):
        for name in _crawl.ament_packages(prefix):
            found.setdefault(name, os.path.join(prefix, "share", name))
    return found


def _in_workspace_src(package: str) -> bool:
    """Whether the working folder is a workspace whose ``src/`` holds ``package`` (at
    ``src/<package>`` or one folder down), as ``colcon``/``catkin`` lay packages out."""
    return package in _workspace_src_packages()


def _workspace_src_packages() -> list[str]:
    """The names of :func:`workspace_src_folders`."""
    return [os.path.basename(folder) for folder in _workspace.src_folders()]


_cheap_names: list[str] = []


def _close_names(package: str) -> list[str]:
    """Names of interface packages robomodel ships, rosbags' stores hold or the package path and
    the workspace have that look like ``package`` (a typo), found with no import of robomodel's
    type machinery."""
    if _never_a_package(package):
        return []
    if not _cheap_names:
        import re

        names = {n[:-3] for n in os.listdir(os.path.join(_MSG, "types")) if n.endswith(".py")}
        interfaces = os.path.join(_MSG, "interfaces")
        if os.path.isdir(interfaces):
            names.update(os.listdir(interfaces))
        for text in _rosbags_store_texts():
            names.update(re.findall(r"'(\w+)/(?:msg|srv|action)/", text))
        _cheap_names.extend(sorted(n for n in names if n.isidentifier() and n[0] != "_"))
    import difflib

    candidates = [*_cheap_names, *_workspace_src_packages(), *_package_path_interfaces()]
    return difflib.get_close_matches(package, candidates, n=3, cutoff=0.8)


def _rosbags_store_texts() -> list[str]:
    """The source of rosbags' type stores, read once (they name every type as 'pkg/kind/Name')."""
    if not _store_texts:
        # Python's path finder alone: importlib.util.find_spec would ask this finder again
        # when rosbags is not installed (an endless recursion)
        spec = importlib.machinery.PathFinder.find_spec("rosbags")
        for folder in (spec.submodule_search_locations or []) if spec else []:
            stores = os.path.join(folder, "typesys", "stores")
            for name in sorted(os.listdir(stores)) if os.path.isdir(stores) else []:
                if name.endswith(".py"):
                    with open(os.path.join(stores, name), encoding="utf-8") as file:
                        _store_texts.append(file.read())
    return _store_texts


def installed() -> ClientLibraryFinder | None:
    """The finder on ``sys.meta_path``, if it is there."""
    for finder in sys.meta_path:
        if isinstance(finder, ClientLibraryFinder):
            return finder
    return None


def install() -> ClientLibraryFinder:
    """Append the finder to ``sys.meta_path`` (once), after Python's own finders, and put the
    one for interface modules under namespace packages first."""
    finder = installed()
    if finder is None:
        finder = ClientLibraryFinder()
        sys.meta_path.append(finder)
    if not any(isinstance(f, _OverNamespaceFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, _OverNamespaceFinder())
    return finder
