"""ament_index_python's package look-ups on robomodel's package discovery
(:mod:`robomodel.clientlibs.package_path`): a package installed in an ``AMENT_PREFIX_PATH`` prefix
has that prefix and ``<prefix>/share/<name>``; a package found in a source folder
(``--package-path``, ``ROS_PACKAGE_PATH``, a workspace's ``src/``) is its own folder for both,
as that is where its files are with no build step.

Resource types other than ``packages`` are read from the prefixes' ament resource index, as
ament_index_python does."""

from __future__ import annotations

import os
from pathlib import Path

from robomodel.clientlibs import package_path
from robomodel.description.packages import Package
from robomodel.errors import PackageNotFoundError as _RobomodelPackageNotFound

__all__ = [
    "PackageNotFoundError",
    "get_package_prefix",
    "get_package_share_directory",
    "get_package_share_path",
    "get_packages_with_prefixes",
    "get_resource",
    "get_resources",
    "get_search_paths",
    "has_resource",
]

_RESOURCE_INDEX = os.path.join("share", "ament_index", "resource_index")


class PackageNotFoundError(KeyError):
    """ament_index_python's: no package of that name (a KeyError, as ament's)."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


def _package(package_name: str) -> Package:
    try:
        return package_path.find(package_name)
    except _RobomodelPackageNotFound as exc:
        raise PackageNotFoundError(str(exc)) from None


def _prefix_of(package: Package) -> Path:
    if package.origin == "AMENT_PREFIX_PATH":
        return package.path.parent.parent  # <prefix>/share/<name>
    return package.path


def get_package_prefix(package_name: str) -> str:
    """The install prefix of ``package_name``; :class:`PackageNotFoundError` if unknown."""
    return str(_prefix_of(_package(package_name)))


def get_package_share_directory(package_name: str, print_warning: bool = True) -> str:
    """The share directory of ``package_name`` (``<prefix>/share/<name>``)."""
    return str(_package(package_name).path)


def get_package_share_path(package_name: str, print_warning: bool = True) -> Path:
    """:func:`get_package_share_directory` as a :class:`pathlib.Path`."""
    return _package(package_name).path


def get_packages_with_prefixes() -> dict[str, str]:
    """Every package robomodel finds, by name, with its prefix."""
    index = package_path.index()
    return {name: str(_prefix_of(index.get(name))) for name in index.names()}


def get_search_paths() -> list[str]:
    """The prefixes of ``AMENT_PREFIX_PATH`` that exist; EnvironmentError if it is unset."""
    value = os.environ.get("AMENT_PREFIX_PATH")
    if not value:
        raise OSError("Environment variable 'AMENT_PREFIX_PATH' is not set or empty")
    return [p for p in value.split(os.pathsep) if p and os.path.exists(p)]


def _resource_prefixes() -> list[str]:
    value = os.environ.get("AMENT_PREFIX_PATH", "")
    return [p for p in value.split(os.pathsep) if p and os.path.exists(p)]


def get_resources(resource_type: str) -> dict[str, str]:
    """The resources of ``resource_type`` by name, with their prefix (``packages``: every
    package robomodel finds)."""
    if resource_type == "packages":
        return get_packages_with_prefixes()
    found: dict[str, str] = {}
    for prefix in _resource_prefixes():
        folder = os.path.join(prefix, _RESOURCE_INDEX, resource_type)
        if os.path.isdir(folder):
            for name in sorted(os.listdir(folder)):
                if not name.startswith("."):
                    found.setdefault(name, prefix)
    return found


def has_resource(resource_type: str, resource_name: str) -> str | None:
    """The prefix that has the resource, or None."""
    return get_resources(resource_type).get(resource_name)


def get_resource(resource_type: str, resource_name: str) -> tuple[str, str]:
    """The content of the resource and its prefix; LookupError if no prefix has it."""
    if resource_type == "packages":
        return "", get_package_prefix(resource_name)
    prefix = has_resource(resource_type, resource_name)
    if prefix is None:
        raise LookupError(
            f"Could not find the resource '{resource_name}' of type '{resource_type}'"
        )
    path = os.path.join(prefix, _RESOURCE_INDEX, resource_type, resource_name)
    with open(path, encoding="utf-8") as file:
        return file.read(), prefix
