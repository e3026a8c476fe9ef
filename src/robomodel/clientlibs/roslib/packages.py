"""``roslib.packages``: a package's folder."""

from __future__ import annotations

from robomodel.clientlibs.rospkg import ResourceNotFound, RosPack

__all__ = ["InvalidROSPkgException", "get_pkg_dir"]


class InvalidROSPkgException(Exception):
    """roslib's: the package is not found."""


def get_pkg_dir(package: str, required: bool = True, ros_root: str | None = None) -> str | None:
    """The folder of ``package``; InvalidROSPkgException (or None when not ``required``)."""
    try:
        return RosPack().get_path(package)
    except ResourceNotFound as exc:
        if required:
            raise InvalidROSPkgException(str(exc)) from None
        return None
