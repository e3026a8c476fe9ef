"""What ``roslaunch --dump-params / --nodes / --args NODE / --files / --ros-args`` print.

The formats are roslaunch 1.16's, byte for byte (``param_dump.py``, ``node_args.py``,
``rlutil.print_file_list``, ``arg_dump.py``); the differential tests compare them with Debian's
roslaunch. One difference: ``--args`` of a node whose package or executable cannot be found is
a clear error instead of roslaunch's traceback.
"""

from __future__ import annotations

import base64
import os
from collections.abc import Mapping
from typing import Any

import yaml

from robomodel.description.packages import PackageIndex
from robomodel.errors import PackageNotFoundError
from robomodel.launch.model import LaunchError, NodeSpec
from robomodel.launch.packages import launch_package_index
from robomodel.launch.ros1.config import Ros1Launch
from robomodel.launch.ros1.params import Binary

__all__ = [
    "find_node_executable",
    "format_dump_params",
    "format_files",
    "format_node_args",
    "format_nodes",
    "format_ros_args",
]

DEFAULT_MASTER_URI = "http://localhost:11311/"


class _Dumper(yaml.SafeDumper):
    pass


def _represent_binary(dumper: yaml.SafeDumper, data: Binary) -> yaml.Node:
    return dumper.represent_scalar(
        "tag:yaml.org,2002:binary", base64.b64encode(data.data).decode("ascii"), style="|"
    )


_Dumper.add_representer(Binary, _represent_binary)


def format_dump_params(launch: Ros1Launch) -> str:
    """``--dump-params``: ``yaml.safe_dump`` of name -> value, then an empty line."""
    return yaml.dump(dict(launch.params), Dumper=_Dumper) + "\n"


def format_nodes(launch: Ros1Launch) -> str:
    """``--nodes``: the resolved names of nodes and tests, one per line."""
    return "\n".join(spec.fqn for spec in (*launch.nodes, *launch.tests)) + "\n"


def format_files(launch: Ros1Launch) -> str:
    """``--files``: every launch file loaded (roslaunch lists a set: order is not defined)."""
    unique = dict.fromkeys(os.path.abspath(p) for p in launch.files)
    return "\n".join(unique) + "\n"


def format_ros_args(launch: Ros1Launch) -> str:
    """``--ros-args``: the top-level file's args, required first, each sorted by name."""
    docs = launch.arg_docs
    if not docs:
        return "No arguments.\n"
    required = sorted((n, d or "undocumented") for n, (d, default) in docs.items() if not default)
    optional = sorted(
        (n, d or "undocumented", default) for n, (d, default) in docs.items() if default
    )
    lines: list[str] = []
    if required:
        lines.append("Required Arguments:")
        lines += [f"  {name}: {doc}" for name, doc in required]
    if optional:
        lines.append("Optional Arguments:")
        lines += [f'  {name} (default "{default}"): {doc}' for name, doc, default in optional]
    return "\n".join(lines) + "\n"


def find_node_executable(spec: NodeSpec, packages: PackageIndex) -> str:
    """The executable of ``pkg``/``type`` as roslaunch finds it (first executable file named
    ``type`` under the package directory).

    Raises:
        LaunchError: unknown package, or no executable of that name in it.
    """
    try:
        root = launch_package_index(packages).find(spec.package)
    except PackageNotFoundError as exc:
        raise LaunchError(str(exc), location=spec.location) from None
    matches: list[str] = []
    # An installed package (<prefix>/share/<pkg>) keeps its nodes in <prefix>/lib/<pkg>, which
    # catkin's find_in_workspaces(['libexec']) searches first (roslib.packages.find_node).
    if root.parent.name == "share":
        libexec = root.parent.parent / "lib" / spec.package / spec.executable
        if libexec.is_file() and os.access(libexec, os.X_OK):
            return str(libexec)
    for directory, subdirs, files in os.walk(root):
        subdirs[:] = sorted(d for d in subdirs if not d.startswith("."))
        if spec.executable in files:
            path = os.path.join(directory, spec.executable)
            if os.access(path, os.X_OK):
                matches.append(path)
    if not matches:
        raise LaunchError(
            f"Cannot locate node of type [{spec.executable}] in package [{spec.package}]. Make "
            "sure file exists in package path and permission is set to executable (chmod +x)",
            location=spec.location,
        )
    return matches[0]


def _env_prefix(spec: NodeSpec, environ: Mapping[str, str]) -> list[str]:
    env: dict[str, str] = {"ROS_MASTER_URI": environ.get("ROS_MASTER_URI", DEFAULT_MASTER_URI)}
    ns = spec.namespace[:-1] if spec.namespace.endswith("/") else spec.namespace
    if ns:
        env["ROS_NAMESPACE"] = ns
    for name, value in spec.env:
        env[name] = value
    return [f'{k}="{v}"' for k, v in env.items() if environ.get(k) != v]


def format_node_args(
    launch: Ros1Launch,
    node_name: str,
    *,
    packages: PackageIndex | None = None,
    environ: Mapping[str, str] | None = None,
) -> str:
    """``--args NODE``: environment assignments, launch-prefix, executable, args, remaps and
    ``__name:=``, as roslaunch builds the node's command line."""
    environ = os.environ if environ is None else environ
    name = node_name if node_name.startswith("/") else "/" + node_name
    matches = [s for s in (*launch.nodes, *launch.tests) if s.fqn == name]
    if not matches:
        names = "\n".join(f" * {s.fqn}" for s in (*launch.nodes, *launch.tests))
        raise LaunchError(
            f"ERROR: Cannot find node named [{name}] in [{launch.path}].\nNode names are:\n{names}"
        )
    if len(matches) > 1:
        raise LaunchError(
            f"ERROR: multiple nodes named [{name}] in [{launch.path}].\nPlease fix the launch "
            "files as duplicate names are not allowed."
        )
    spec = matches[0]
    executable = find_node_executable(spec, packages or PackageIndex())
    import shlex

    prefix = shlex.split(spec.launch_prefix) if spec.launch_prefix else []
    remaps = [f"{a}:={b}" for a, b in spec.remaps] + [f"__name:={spec.name}"]
    words: list[Any] = [
        *_env_prefix(spec, environ),
        *prefix,
        executable,
        *spec.args,
        *remaps,
    ]
    return " ".join(words) + "\n"
