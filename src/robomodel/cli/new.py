"""``robomodel new``: create a robot description package (catkin_create_pkg, ros2 pkg create)."""

from __future__ import annotations

import argparse
from typing import Any

from robomodel.cli._verbs import verb_help
from robomodel.description.scaffold import BuildType, PackageSpec, create_description_package

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "new",
        help=verb_help("new"),
        description=(
            "Create a robot description package. Takes catkin_create_pkg's arguments "
            "(robomodel new NAME DEP...: a ROS 1 catkin package) and ros2 pkg create's "
            "(robomodel new --build-type ament_cmake NAME --dependencies DEP...: a ROS 2 "
            "package). Writes package.xml with the dependencies and CMakeLists.txt as those "
            "tools do, plus urdf/, meshes/, launch/, rviz/ and config/."
        ),
    )
    parser.add_argument("name", metavar="NAME", help="package name, e.g. gripper_description")
    parser.add_argument(
        "deps",
        nargs="*",
        metavar="DEPENDENCY",
        help="packages it depends on, as catkin_create_pkg takes them",
    )
    parser.add_argument(
        "--dependencies",
        nargs="+",
        default=[],
        metavar="DEPENDENCY",
        help="packages it depends on, as ros2 pkg create takes them (implies ament_cmake)",
    )
    parser.add_argument(
        "--build-type",
        choices=[b.value for b in BuildType],
        help="catkin (ROS 1; the default) or ament_cmake (ROS 2; the default with --dependencies)",
    )
    parser.add_argument(
        "--dir",
        "--destination-directory",
        dest="dir",
        default=".",
        help="where to create it (default: .)",
    )
    parser.add_argument("-D", "--description", help="the package.xml description")
    parser.add_argument("-l", "--license", default="TODO", help="the package.xml license")
    parser.add_argument(
        "-m", "--maintainer-name", help="the package.xml maintainer (default: your user name)"
    )
    parser.add_argument("--maintainer-email", help="default: USER@todo.todo")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    if args.build_type is not None:
        build_type = BuildType(args.build_type)
    else:
        build_type = BuildType.AMENT_CMAKE if args.dependencies else BuildType.CATKIN
    spec = PackageSpec(
        args.name,
        build_type=build_type,
        dependencies=tuple(dict.fromkeys([*args.deps, *args.dependencies])),
        description=args.description,
        license=args.license,
        maintainer_name=args.maintainer_name,
        maintainer_email=args.maintainer_email,
    )
    target = create_description_package(spec, args.dir)
    robot = args.name.removesuffix("_description") or args.name
    print(f"Created {build_type.value} package {target}")
    print(f"  check it:  robomodel check {target}/urdf/{robot}.urdf")
    return 0
