"""rospkg's package look-ups on robomodel's package discovery
(:mod:`robomodel.clientlibs.package_path`): ``RosPack().get_path``, ``list``, ``ResourceNotFound``
and the package path's variables."""

from __future__ import annotations

import os
from typing import Any

from robomodel.clientlibs import package_path
from robomodel.description.packages import PackageIndex
from robomodel.errors import PackageNotFoundError

__all__ = [
    "ResourceNotFound",
    "RosPack",
    "get_ros_package_path",
    "get_ros_paths",
]


class ResourceNotFound(Exception):
    """rospkg's: no package (resource) of that name."""

    def __init__(self, msg: str, ros_paths: list[str] | None = None) -> None:
        super().__init__(msg)
        self.ros_paths = ros_paths

    def __str__(self) -> str:
        text = str(self.args[0])
        if self.ros_paths:
            for i, path in enumerate(self.ros_paths):
                text += f"\nROS path [{i}]={path}"
        return text


def get_ros_package_path(env: dict[str, str] | None = None) -> str | None:
    """``ROS_PACKAGE_PATH``, or None when unset."""
    return (os.environ if env is None else env).get("ROS_PACKAGE_PATH")


def get_ros_paths(env: dict[str, str] | None = None) -> list[str]:
    """The folders rospkg searches: ``ROS_PACKAGE_PATH``'s entries."""
    value = get_ros_package_path(env) or ""
    return [p for p in value.split(os.pathsep) if p]


class RosPack:
    """rospkg's package crawler: packages by name, from the package path."""

    def __init__(self, ros_paths: list[str] | None = None) -> None:
        self._ros_paths = ros_paths
        self._index: PackageIndex | None = None

    @classmethod
    def get_instance(cls, ros_paths: list[str] | None = None) -> RosPack:
        return cls(ros_paths)

    @property
    def ros_paths(self) -> list[str]:
        return list(self._ros_paths) if self._ros_paths is not None else get_ros_paths()

    def _packages(self) -> PackageIndex:
        if self._index is None:
            if self._ros_paths is not None:  # only the folders given, as rospkg
                self._index = PackageIndex(package_paths=self._ros_paths, use_environment=False)
            else:
                self._index = package_path.index()
        return self._index

    def get_path(self, name: str) -> str:
        """The folder of package ``name``; :class:`ResourceNotFound` if it is unknown."""
        try:
            return str(self._packages().find(name))
        except PackageNotFoundError as exc:
            raise ResourceNotFound(str(exc), ros_paths=self.ros_paths) from None

    def list(self) -> list[str]:
        """The names of every package found."""
        return list(self._packages().names())

    def get_depends(self, name: str, implicit: bool = True) -> Any:
        raise NotImplementedError(
            "rospkg.RosPack.get_depends: robomodel finds packages but does not read their "
            "dependencies"
        )

    def get_manifest(self, name: str) -> Any:
        raise NotImplementedError("rospkg.RosPack.get_manifest: robomodel reads no manifests")


class RosStack:
    """rospkg's stack crawler: ROS 1's stacks are not modelled."""

    def __init__(self, ros_paths: list[str] | None = None) -> None:
        raise NotImplementedError("rospkg.RosStack: robomodel knows packages, not stacks")
