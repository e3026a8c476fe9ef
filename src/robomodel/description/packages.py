"""ROS package discovery and resource URI resolution (``package://``, ``file://``, ``$(find)``).

Packages are found the ways ROS finds them, in this priority order (the first match wins):

1. explicit ``NAME=DIR`` mappings (``--package``), for install layouts that differ from the source;
2. ``--package-path DIR`` entries, scanned recursively for ``package.xml`` as rospack does;
3. ``ROS_PACKAGE_PATH`` entries, scanned the same way;
4. ``AMENT_PREFIX_PATH`` entries, where a package lives in ``<prefix>/share/<name>`` and is
   known by ament's resource-index marker ``share/ament_index/resource_index/packages/<name>``
   (or, without a marker, by ``share/<name>/package.xml``);
5. the package that contains the input file (the nearest ``package.xml`` above it);
6. the workspace of the input file (the folders around its package);
7. the robots of PyPI's ``example-robot-data``, where it is installed: each
   ``robots/<name>_description`` folder is the package ``<name>_description`` (so the UR
   tutorials' ``package://ur_description/meshes/ur5/visual/base.dae`` resolves), and the
   wheel's ``share/example-robot-data`` is ``example-robot-data``. Last, so a user's own package
   of the same name always wins; ``ROBOMODEL_EXAMPLE_ROBOT_DATA=0`` turns it off.

The input file's own package thus applies only where ROS would find no package of that name at
all; ahead of the folders around it, so that a copy of a package beside the original uses its
own files. Paths are kept as given, never replaced by a symlink's target: in a ``colcon build
--symlink-install`` prefix, a launch file that is a symlink into the source tree still finds its
package in ``<prefix>/share/<name>``, as ``ros2 launch`` and ``rospack`` do.

A scanned directory that holds a ``package.xml`` is a package: its name is the manifest's
``<name>`` and the scan does not descend further (rospack's rule). Directories holding
``CATKIN_IGNORE``, ``COLCON_IGNORE`` or ``AMENT_IGNORE`` and hidden directories are skipped.
"""

from __future__ import annotations

import copy
import functools
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import unquote, urlparse

from robomodel.description import _crawl
from robomodel.errors import PackageNotFoundError, PathEscapeError, RobomodelError

__all__ = [
    "Package",
    "PackageIndex",
    "find_enclosing_package",
    "index_from_options",
    "parse_package_option",
]


@dataclass(frozen=True, slots=True)
class Package:
    """A ROS package: its name and the directory that ``$(find name)`` returns."""

    name: str
    path: Path
    origin: str  # which search source found it: "explicit", "package-path", "ROS_PACKAGE_PATH", ...


def parse_package_option(text: str) -> tuple[str, Path]:
    """Parse a ``NAME=DIR`` command-line option into ``(name, path)``."""
    name, sep, directory = text.partition("=")
    if not sep or not name.strip() or not directory.strip():
        raise RobomodelError(f"--package expects NAME=DIR, got '{text}'")
    return name.strip(), Path(directory.strip()).expanduser()


def _scan_tree(root: Path, found: dict[str, Path]) -> None:
    """Collect the packages below ``root`` (rospack's crawl, :mod:`._crawl`)."""
    crawled: dict[str, str] = {}
    _crawl.scan_tree(str(root), crawled)
    for name, folder in crawled.items():
        found.setdefault(name, Path(folder))


_ERD_SWITCH = "ROBOMODEL_EXAMPLE_ROBOT_DATA"


@functools.lru_cache(maxsize=1)
def example_robot_data_packages() -> tuple[tuple[str, Path], ...]:
    """``(name, dir)`` of example-robot-data's description packages, if the wheel is installed.

    The wheel (a cmeel package) has no Python module: its files are under
    ``cmeel.prefix/share/example-robot-data`` of the site-packages folder it was installed
    into, looked for on ``sys.path`` (``importlib.metadata`` would cost every command the
    ``email`` package's import).
    """
    import sys

    share = next(
        (
            Path(entry, "cmeel.prefix", "share", "example-robot-data")
            for entry in sys.path
            if entry and os.path.isdir(os.path.join(entry, "cmeel.prefix"))
        ),
        None,
    )
    if share is None:
        return ()
    try:
        robots = sorted(os.scandir(share / "robots"), key=lambda e: e.name)
    except OSError:
        return ()
    found = [
        (e.name, Path(e.path)) for e in robots if e.is_dir() and e.name.endswith("_description")
    ]
    return (("example-robot-data", share), *found)


def _absolute(path: Path) -> Path:
    """``path`` made absolute against the working folder, symlinks kept (``os.path.abspath``)."""
    return path if path.is_absolute() else Path(os.path.abspath(path))


def _split_env_paths(value: str | None) -> list[Path]:
    return [Path(p) for p in _crawl.split_paths(value)]


class PackageIndex:
    """Finds ROS packages by name and resolves resource URIs against them.

    Scanning is lazy: nothing touches the file system until the first lookup.

    Args:
        package_paths: Directories to scan recursively for ``package.xml``.
        packages: Explicit ``name -> directory`` mappings; they take precedence.
        use_environment: Also read ``ROS_PACKAGE_PATH`` and ``AMENT_PREFIX_PATH``.
        environ: The environment to read (defaults to ``os.environ``).
        fallback_paths: Directories scanned after every other source.
        example_robot_data: Offer example-robot-data's robots (last); ``None``: when
            ``use_environment`` and ``ROBOMODEL_EXAMPLE_ROBOT_DATA`` is not ``0``.
    """

    def __init__(
        self,
        *,
        package_paths: Iterable[str | os.PathLike[str]] = (),
        packages: Mapping[str, str | os.PathLike[str]] | None = None,
        use_environment: bool = True,
        environ: Mapping[str, str] | None = None,
        fallback_paths: Iterable[str | os.PathLike[str]] = (),
        example_robot_data: bool | None = None,
    ) -> None:
        self._explicit = {name: Path(path) for name, path in (packages or {}).items()}
        self._package_paths = tuple(Path(p) for p in package_paths)
        self._fallback_paths = tuple((Path(p), f"the folders around {p}") for p in fallback_paths)
        self._own: tuple[Package, ...] = ()
        env = os.environ if environ is None else environ
        self._ros_package_path = (
            _split_env_paths(env.get("ROS_PACKAGE_PATH")) if use_environment else []
        )
        self._ament_prefixes = (
            _split_env_paths(env.get("AMENT_PREFIX_PATH")) if use_environment else []
        )
        if example_robot_data is None:
            example_robot_data = use_environment and env.get(_ERD_SWITCH, "1") != "0"
        self._bundled = example_robot_data_packages() if example_robot_data else ()
        self._index: dict[str, Package] | None = None

    @property
    def searched(self) -> tuple[str, ...]:
        """The places this index looks in, as the user names them (flags, variables)."""
        places = [f"--package {n}={p}" for n, p in self._explicit.items()]
        places += [f"--package-path {p}" for p in self._package_paths]
        places += [f"ROS_PACKAGE_PATH {p}" for p in self._ros_package_path]
        places += [f"AMENT_PREFIX_PATH {p}" for p in self._ament_prefixes]
        places += [label for _, label in self._fallback_paths]
        if self._bundled:
            places.append(f"example-robot-data {self._bundled[0][1]}")
        return tuple(dict.fromkeys(places))

    def _build(self) -> dict[str, Package]:
        # Paths made absolute (not resolved: a symlink stays as given), so that a package found
        # through a relative `--package-path examples` does not resolve includes relative to
        # the including file's folder a second time.
        index: dict[str, Package] = {}
        for name, path in self._explicit.items():
            index[name] = Package(name, _absolute(path), "explicit")
        for origin, roots in (
            ("package-path", self._package_paths),
            ("ROS_PACKAGE_PATH", self._ros_package_path),
        ):
            for root in roots:
                found: dict[str, Path] = {}
                _scan_tree(_absolute(root), found)
                for name, path in found.items():
                    index.setdefault(name, Package(name, path, origin))
        for prefix in map(_absolute, self._ament_prefixes):
            for name in _crawl.ament_packages(str(prefix)):
                index.setdefault(name, Package(name, prefix / "share" / name, "AMENT_PREFIX_PATH"))
        for package in self._own:  # only where the search paths know no such name, as ROS's search
            index.setdefault(package.name, package)
        for root, _ in self._fallback_paths:
            found = {}
            _scan_tree(_absolute(root), found)
            for name, path in found.items():
                index.setdefault(name, Package(name, path, "workspace"))
        for name, path in self._bundled:
            index.setdefault(name, Package(name, path, "example-robot-data"))
        return index

    def with_workspace_of(self, path: str | os.PathLike[str]) -> PackageIndex:
        """This index, also searching (last) the workspace around ``path``.

        The package enclosing ``path`` and its sibling packages are found without any setup,
        as they would be in a sourced ROS workspace: ``robomodel check urdf/robot.xacro`` run
        inside a package resolves ``$(find that_package)``. The enclosing package comes after
        the search paths and before the folders around it (a copy beside the original resolves
        to the copy; one on ``ROS_PACKAGE_PATH`` wins, as in ROS).
        """
        enclosing = find_enclosing_package(path)
        if enclosing is None:
            return self
        name = _crawl.manifest_name(str(enclosing / "package.xml")) or enclosing.name
        clone = self.with_fallback(
            enclosing.parent, label=f"the folders beside the input's package ({enclosing.parent})"
        )
        if name not in {p.name for p in self._own}:
            clone._own = (*self._own, Package(name, enclosing, "input"))
        return clone

    def with_fallback(
        self, directory: str | os.PathLike[str], *, label: str | None = None
    ) -> PackageIndex:
        """This index, also scanning ``directory`` for packages, after every other source
        (``label``: how error messages name the place)."""
        clone = copy.copy(self)
        place = (Path(directory), label or f"the folders around {directory}")
        clone._fallback_paths = (*self._fallback_paths, place)
        clone._index = None
        return clone

    def _packages(self) -> dict[str, Package]:
        if self._index is None:
            self._index = self._build()
        return self._index

    def names(self) -> tuple[str, ...]:
        """All package names this index can find, sorted."""
        return tuple(sorted(self._packages()))

    def get(self, name: str) -> Package:
        """Return the package called ``name`` or raise :class:`PackageNotFoundError`."""
        packages = self._packages()
        try:
            return packages[name]
        except KeyError:
            raise PackageNotFoundError(name, sorted(packages), self.searched) from None

    def find(self, name: str) -> Path:
        """Return the directory of package ``name`` (what ``$(find name)`` expands to)."""
        return self.get(name).path

    def resolve(self, uri: str, *, base_dir: str | os.PathLike[str] | None = None) -> Path:
        """Resolve a resource reference to a file path.

        Accepts ``package://pkg/rel/path``, ``file:///abs/path``, absolute paths and paths
        relative to ``base_dir`` (the directory of the file that mentions them).

        Raises:
            PackageNotFoundError: the package is unknown.
            PathEscapeError: a ``package://`` path leaves its package directory.
        """
        if uri.startswith("package://"):
            rest = uri[len("package://") :]
            name, _, relative = rest.partition("/")
            root = self.find(name)
            return _join_inside(root, relative, uri, name)
        if uri.startswith("file://"):
            return Path(unquote(urlparse(uri).path))
        path = Path(uri)
        if path.is_absolute() or base_dir is None:
            return path
        return Path(os.path.normpath(Path(base_dir) / path))

    def package_of(self, path: str | os.PathLike[str]) -> Package | None:
        """Return the known package whose directory contains ``path``, if any."""
        target = os.path.normpath(os.path.abspath(path))
        best: Package | None = None
        for package in self._packages().values():
            root = os.path.normpath(os.path.abspath(package.path))
            if (target == root or target.startswith(root + os.sep)) and (
                best is None or len(str(package.path)) > len(str(best.path))
            ):
                best = package
        return best


def _join_inside(root: Path, relative: str, uri: str, package: str) -> Path:
    root_norm = os.path.normpath(os.path.abspath(root))
    joined = os.path.normpath(os.path.join(root_norm, unquote(relative)))
    if joined != root_norm and not joined.startswith(root_norm + os.sep):
        raise PathEscapeError(uri, package, str(root))
    return Path(joined)


def find_enclosing_package(path: str | os.PathLike[str]) -> Path | None:
    """The nearest directory at or above ``path`` holding a ``package.xml``.

    The path is made absolute as given, not resolved: a symlinked file of an install prefix
    belongs to the prefix's package, not to the source folder its target is in.
    """
    current = Path(os.path.abspath(path))
    if current.is_file() or not current.exists():
        current = current.parent
    for directory in (current, *current.parents):
        if (directory / "package.xml").is_file():
            return directory
    return None


def index_from_options(
    package_paths: Sequence[str | os.PathLike[str]] = (),
    package_options: Sequence[str] = (),
) -> PackageIndex:
    """Build an index from CLI-style ``--package-path`` and ``--package NAME=DIR`` values."""
    explicit = dict(parse_package_option(opt) for opt in package_options)
    return PackageIndex(package_paths=package_paths, packages=explicit)
