"""Where launch files find packages: the user's (``--package-path``, ``ROS_PACKAGE_PATH``,
``AMENT_PREFIX_PATH``, the launch file's own workspace) and, last, the ones robomodel ships.

robomodel ships small packages under ``robomodel/launch/share/`` that launch files name
(``$(find xacro)/xacro``, ``$(find gazebo_ros)/launch/empty_world.launch``): a real package of
the same name on the user's paths always wins.
"""

from __future__ import annotations

from pathlib import Path

from robomodel.description.packages import PackageIndex

__all__ = ["SHARE", "launch_package_index"]

SHARE = Path(__file__).resolve().parent / "share"


def launch_package_index(index: PackageIndex) -> PackageIndex:
    """``index`` with robomodel's built-in launch packages as the last source."""
    names = ", ".join(sorted(p.name for p in SHARE.iterdir() if p.is_dir()))
    return index.with_fallback(SHARE, label=f"robomodel's built-in packages ({names})")
