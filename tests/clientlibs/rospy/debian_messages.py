"""Python message modules for Debian's Python (its genpy and real actionlib), generated as
catkin builds them, for the tests where Debian's ROS 1 and robomodel talk over actions."""

from __future__ import annotations

import subprocess
from pathlib import Path

__all__ = ["DEBIAN_PYTHON", "GENACTION", "GENPY", "debian_messages", "write_definitions"]

DEBIAN_PYTHON = "/usr/bin/python3"
GENPY = Path("/usr/lib/genpy")
GENACTION = Path("/usr/lib/actionlib_msgs/genaction.py")
PACKAGES = Path(__file__).parent / "packages"
_SEPARATOR = "\n" + "=" * 80 + "\nMSG: "


def write_definitions(include: Path, names: tuple[str, ...]) -> None:
    """The ``.msg`` files of ROS 1 types ``names`` and of every type they hold, written from
    robomodel's Noetic definitions to ``include/<package>/msg/``, for genpy's ``-I`` flags
    (Debian ships the Python modules of std_msgs, geometry_msgs and actionlib_msgs but not
    their .msg files)."""
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type_named

    for name in names:
        first, *others = ros1_type_named(name).definition.split(_SEPARATOR)
        for dep_name, text in [(name, first), *(o.split("\n", 1) for o in others)]:
            package, stem = dep_name.split("/")
            path = include / package / "msg" / f"{stem}.msg"
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)


def debian_messages(work: Path) -> Path:
    """The Python messages of actionlib_tutorials and of ROS 1's control_msgs (the ROS 1 files
    robomodel vendors) for Debian's Python, as catkin builds them: genaction's seven messages
    of each ``.action`` file, then genpy's generator. Debian ships std_msgs' and
    actionlib_msgs' Python modules but neither their .msg files nor trajectory_msgs: those
    definitions are written out from robomodel's Noetic ones (rosbags' store), and
    trajectory_msgs is generated too. The folder to put on PYTHONPATH."""
    from robomodel.runtime.transport.ros1.ros1_types import DEFINITIONS

    include = work / "include"
    write_definitions(include, ("std_msgs/Header", "actionlib_msgs/GoalID",
                                "actionlib_msgs/GoalStatus", "trajectory_msgs/JointTrajectory"))  # fmt: skip
    python = work / "python"
    tutorials = _genaction(PACKAGES / "actionlib_tutorials" / "action" / "Fibonacci.action",
                           work / "actionlib_tutorials")  # fmt: skip
    _genpy(python, "actionlib_tutorials", tutorials, [tutorials[0].parent], include)
    trajectory = sorted((include / "trajectory_msgs" / "msg").glob("*.msg"))
    _genpy(python, "trajectory_msgs", trajectory, [], include)
    control = DEFINITIONS / "control_msgs"
    actions = _genaction(control / "action" / "FollowJointTrajectory.action", work / "control")
    tolerance = control / "msg" / "JointTolerance.msg"
    own = [actions[0].parent, tolerance.parent]
    _genpy(python, "control_msgs", [*actions, tolerance], own, include)
    return python


def _genaction(action: Path, out: Path) -> list[Path]:
    """actionlib_msgs' genaction.py on ``action``: its seven .msg files."""
    subprocess.run([DEBIAN_PYTHON, str(GENACTION), str(action), "-o", str(out)],
                   check=True, capture_output=True)  # fmt: skip
    files = sorted(out.glob("*.msg"))
    assert len(files) == 7, files
    return files


def _genpy(python: Path, package: str, files: list[Path], own: list[Path], include: Path) -> None:
    """genpy's generator: ``package``'s Python messages of ``files`` under ``python``; ``own``
    the folders of the package's own definitions, ``include`` the other packages' (one folder
    per package)."""
    flags = [f"-I{package}:{folder}" for folder in own]
    flags += [f"-I{folder.name}:{folder / 'msg'}" for folder in sorted(include.iterdir())]
    out = python / package
    for argv in (flags + [str(f) for f in files], ["--initpy"]):
        subprocess.run(
            [DEBIAN_PYTHON, str(GENPY / "genmsg_py.py"), "-p", package,
             "-o", str(out / "msg"), *argv],
            check=True, capture_output=True,
        )  # fmt: skip
    (out / "__init__.py").write_text("")
