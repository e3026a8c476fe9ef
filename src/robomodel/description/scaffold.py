"""``robomodel new``: a robot description package, as ``catkin_create_pkg`` or
``ros2 pkg create`` writes it, with the folders of a description package.

The manifest and CMakeLists.txt follow those tools (catkin_pkg's ``package_templates.py`` and
ros2pkg's ``ament_cmake`` resource): ``catkin_create_pkg NAME DEP...`` lists each dependency as
``build_depend``, ``build_export_depend`` and ``exec_depend`` (format 2) and finds them as catkin
COMPONENTS; ``ros2 pkg create --build-type ament_cmake NAME --dependencies DEP...`` lists each
as ``depend`` (format 3) and finds it with ``find_package``. Both tools make ``include/NAME``
and ``src/`` for C++ (catkin: when ``roscpp`` is a dependency; ``src/`` also for ``rospy``).
Beside them go ``urdf/`` (a xacro and its plain URDF twin), ``meshes/``, ``launch/`` (the
ROS 1 or ROS 2 display launch file), ``rviz/``, ``config/`` and a README.

The package is created in a temporary directory beside the target and renamed into place, so a
failure never leaves half a package behind.
"""

from __future__ import annotations

import enum
import getpass
import html
import os
import re
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path
from string import Template

from robomodel.errors import RobomodelError

__all__ = ["PACKAGE_NAME_RE", "BuildType", "PackageSpec", "create_description_package"]

# REP 144: lower case letters, digits and underscores, starting with a letter.
PACKAGE_NAME_RE = re.compile(r"^[a-z][a-z0-9_]*$")

_TEMPLATE_DIR = Path(__file__).with_name("templates")

# What the display launch files need, listed when no dependencies are given (run time only).
_CATKIN_RUN_DEPENDS = (
    "joint_state_publisher",
    "joint_state_publisher_gui",
    "robot_state_publisher",
    "rviz",
    "urdf",
    "xacro",
)
_AMENT_RUN_DEPENDS = (
    "joint_state_publisher",
    "joint_state_publisher_gui",
    "launch",
    "launch_ros",
    "robot_state_publisher",
    "rviz2",
    "urdf",
    "xacro",
)
# ros2 pkg create's test dependencies of an ament_cmake package
_AMENT_TEST_DEPENDS = ("ament_lint_auto", "ament_lint_common")
_SHARED_FOLDERS = "urdf meshes launch rviz config"


class BuildType(enum.Enum):
    """The package's build type: ``catkin`` (ROS 1) or ``ament_cmake`` (ROS 2)."""

    CATKIN = "catkin"
    AMENT_CMAKE = "ament_cmake"


@dataclass(frozen=True, slots=True)
class PackageSpec:
    """What ``catkin_create_pkg`` / ``ros2 pkg create`` are told about a new package.

    Attributes:
        name: the package name (REP 144).
        build_type: catkin (ROS 1) or ament_cmake (ROS 2).
        dependencies: the packages it depends on, as given; empty lists what its display
            launch file needs, as run-time dependencies.
        description: the manifest's description (default: the tools' ``The NAME package``).
        license: the manifest's license (default ``TODO``, as both tools write).
        maintainer_name: default: the user name, as both tools write.
        maintainer_email: default: ``USER@todo.todo``, as both tools write.
    """

    name: str
    build_type: BuildType = BuildType.CATKIN
    dependencies: tuple[str, ...] = ()
    description: str | None = None
    license: str = "TODO"
    maintainer_name: str | None = None
    maintainer_email: str | None = None


def create_description_package(
    spec: PackageSpec | str, directory: str | os.PathLike[str] = "."
) -> Path:
    """Create the package ``spec`` (or a catkin package of that name) under ``directory``.

    Returns:
        The new package directory.

    Raises:
        RobomodelError: a name is not a valid ROS package name, or the target exists.
    """
    if isinstance(spec, str):
        spec = PackageSpec(spec)
    for name in (spec.name, *spec.dependencies):
        if not PACKAGE_NAME_RE.match(name):
            raise RobomodelError(
                f"'{name}' is not a valid ROS package name; use lower-case letters, digits and "
                "underscores, starting with a letter (for example my_robot_description)"
            )
    parent = Path(directory)
    target = parent / spec.name
    if target.exists():
        raise RobomodelError(f"'{target}' already exists; choose another name or --dir")
    parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{spec.name}.", dir=parent))
    try:
        for relative, text in package_files(spec).items():
            out = staging / relative
            out.parent.mkdir(parents=True, exist_ok=True)
            out.write_text(text)
        for folder in _source_folders(spec):
            (staging / folder).mkdir(parents=True)
        os.replace(staging, target)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return target


def package_files(spec: PackageSpec) -> dict[str, str]:
    """The package's files: path relative to the package → text."""
    robot = spec.name.removesuffix("_description") or spec.name
    catkin = spec.build_type is BuildType.CATKIN
    values = {
        "package": spec.name,
        "robot": robot,
        "launch_help": (
            f"`roslaunch {spec.name} display.launch` in a catkin workspace; without ROS, "
            f"`robomodel launch {spec.name} display.launch`"
            if catkin
            else f"`ros2 launch {spec.name} display.launch.py` in a colcon workspace; without "
            f"ROS, `robomodel launch {spec.name} display.launch.py`"
        ),
    }
    templates = {
        f"urdf/{robot}.urdf.xacro": "robot.urdf.xacro.in",
        f"urdf/{robot}.urdf": "robot.urdf.in",
        "launch/display.launch" if catkin else "launch/display.launch.py": (
            "display.launch.in" if catkin else "display.launch.py.in"
        ),
        "config/joint_limits.yaml": "joint_limits.yaml.in",
        "README.md": "README.md.in",
    }
    files = {
        "package.xml": _catkin_package_xml(spec) if catkin else _ament_package_xml(spec),
        "CMakeLists.txt": _catkin_cmakelists(spec) if catkin else _ament_cmakelists(spec),
    }
    for relative, template in templates.items():
        files[relative] = Template((_TEMPLATE_DIR / template).read_text()).substitute(values)
    files["meshes/.gitkeep"] = ""
    files["rviz/.gitkeep"] = ""
    return files


def _source_folders(spec: PackageSpec) -> tuple[str, ...]:
    """The C++/Python source folders the ROS tool would make (empty, as it makes them)."""
    include, src = f"include/{spec.name}", "src"
    if spec.build_type is BuildType.AMENT_CMAKE:
        return (include, src)
    if "roscpp" in spec.dependencies:
        return (include, src)
    return (src,) if "rospy" in spec.dependencies else ()


def _manifest_head(spec: PackageSpec, package_format: int) -> list[str]:
    user = getpass.getuser()
    name = spec.maintainer_name or user
    email = spec.maintainer_email or f"{user}@todo.todo"
    description = spec.description or f"The {spec.name} package"
    schema = f"http://download.ros.org/schema/package_format{package_format}.xsd"
    return [
        '<?xml version="1.0"?>',
        f'<?xml-model href="{schema}" schematypens="http://www.w3.org/2001/XMLSchema"?>',
        f'<package format="{package_format}">',
        f"  <name>{spec.name}</name>",
        "  <version>0.0.0</version>",
        f"  <description>{html.escape(description)}</description>",
        f'  <maintainer email="{html.escape(email)}">{html.escape(name)}</maintainer>',
        f"  <license>{html.escape(spec.license)}</license>",
        "",
    ]


def _tags(tag: str, names: tuple[str, ...]) -> list[str]:
    return [f"  <{tag}>{name}</{tag}>" for name in names]


def _catkin_package_xml(spec: PackageSpec) -> str:
    deps = tuple(sorted(spec.dependencies))
    lines = [*_manifest_head(spec, 2), *_tags("buildtool_depend", ("catkin",))]
    if deps:
        for tag in ("build_depend", "build_export_depend", "exec_depend"):
            lines += _tags(tag, deps)
    else:
        lines += _tags("exec_depend", _CATKIN_RUN_DEPENDS)
    lines += ["", "  <export>", "  </export>", "</package>", ""]
    return "\n".join(lines)


def _ament_package_xml(spec: PackageSpec) -> str:
    lines = [*_manifest_head(spec, 3), *_tags("buildtool_depend", ("ament_cmake",)), ""]
    if spec.dependencies:
        lines += _tags("depend", spec.dependencies)
    else:
        lines += _tags("exec_depend", _AMENT_RUN_DEPENDS)
    lines += ["", *_tags("test_depend", _AMENT_TEST_DEPENDS), ""]
    lines += ["  <export>", "    <build_type>ament_cmake</build_type>", "  </export>"]
    lines += ["</package>", ""]
    return "\n".join(lines)


def _catkin_cmakelists(spec: PackageSpec) -> str:
    deps = sorted(spec.dependencies)
    components = "".join(f"\n  {d}" for d in deps)
    lines = [
        "cmake_minimum_required(VERSION 3.0.2)",
        f"project({spec.name})",
        "",
        f"find_package(catkin REQUIRED COMPONENTS{components}\n)"
        if deps
        else "find_package(catkin REQUIRED)",
        "",
        "catkin_package(",
        f"#  CATKIN_DEPENDS {' '.join(deps)}" if deps else "#  CATKIN_DEPENDS other_catkin_pkg",
        ")",
        "",
    ]
    if deps:
        lines += ["include_directories(", "  ${catkin_INCLUDE_DIRS}", ")", ""]
    lines += [
        f"install(DIRECTORY {_SHARED_FOLDERS}",
        "  DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}",
        ")",
        "",
    ]
    return "\n".join(lines)


def _ament_cmakelists(spec: PackageSpec) -> str:
    lines = [
        "cmake_minimum_required(VERSION 3.8)",
        f"project({spec.name})",
        "",
        'if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")',
        "  add_compile_options(-Wall -Wextra -Wpedantic)",
        "endif()",
        "",
        "# find dependencies",
        "find_package(ament_cmake REQUIRED)",
        *(f"find_package({d} REQUIRED)" for d in spec.dependencies),
        "",
        f"install(DIRECTORY {_SHARED_FOLDERS}",
        "  DESTINATION share/${PROJECT_NAME}",
        ")",
        "",
        "if(BUILD_TESTING)",
        "  find_package(ament_lint_auto REQUIRED)",
        "  set(ament_cmake_copyright_FOUND TRUE)",
        "  set(ament_cmake_cpplint_FOUND TRUE)",
        "  ament_lint_auto_find_test_dependencies()",
        "endif()",
        "",
        "ament_package()",
        "",
    ]
    return "\n".join(lines)
