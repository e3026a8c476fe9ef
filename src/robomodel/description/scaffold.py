"""``robomodel new``: a robot description package laid out as the ROS courses teach.

The package is created in a temporary directory beside the target and renamed into place, so a
failure never leaves half a package behind.
"""

from __future__ import annotations

import os
import re
import shutil
import tempfile
from pathlib import Path
from string import Template

from robomodel.errors import RobomodelError

__all__ = ["PACKAGE_NAME_RE", "create_description_package"]

# REP 144: lower case letters, digits and underscores, starting with a letter.
PACKAGE_NAME_RE = re.compile(r"^[a-z][a-z0-9_]*$")

_TEMPLATE_DIR = Path(__file__).with_name("templates")

# (template file, path in the package); ${package} and ${robot} are substituted.
_FILES = (
    ("package.xml.in", "package.xml"),
    ("CMakeLists.txt.in", "CMakeLists.txt"),
    ("robot.urdf.xacro.in", "urdf/${robot}.urdf.xacro"),
    ("robot.urdf.in", "urdf/${robot}.urdf"),
    ("display.launch.py.in", "launch/display.launch.py"),
    ("display.launch.in", "launch/display.launch"),
    ("joint_limits.yaml.in", "config/joint_limits.yaml"),
    ("README.md.in", "README.md"),
)


def create_description_package(name: str, directory: str | os.PathLike[str] = ".") -> Path:
    """Create package ``name`` (e.g. ``arm_description``) under ``directory``.

    Returns:
        The new package directory.

    Raises:
        RobomodelError: the name is not a valid ROS package name or the target exists.
    """
    if not PACKAGE_NAME_RE.match(name):
        raise RobomodelError(
            f"'{name}' is not a valid ROS package name; use lower-case letters, digits and "
            "underscores, starting with a letter (for example my_robot_description)"
        )
    robot = name.removesuffix("_description") or name
    parent = Path(directory)
    target = parent / name
    if target.exists():
        raise RobomodelError(f"'{target}' already exists; choose another name or --dir")
    parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{name}.", dir=parent))
    try:
        values = {"package": name, "robot": robot}
        for template_name, relative in _FILES:
            text = Template((_TEMPLATE_DIR / template_name).read_text()).substitute(values)
            out = staging / Template(relative).substitute(values)
            out.parent.mkdir(parents=True, exist_ok=True)
            out.write_text(text)
        (staging / "meshes").mkdir()
        (staging / "meshes" / ".gitkeep").write_text("")
        os.replace(staging, target)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return target
