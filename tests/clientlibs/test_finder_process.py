"""The import finder in fresh interpreters (as a user runs ``python3 my_node.py``): a user's
interface package in the workspace's ``src/`` and on ``ROS_PACKAGE_PATH``, in both flavours; a
typo'd package name; and a real installation on ``PYTHONPATH`` winning over robomodel."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _run(code: str, cwd: Path, **env: str) -> subprocess.CompletedProcess[str]:
    full = dict(os.environ, ROBOMODEL_CLIENTLIBS="1", **env)
    full.pop("ROS_PACKAGE_PATH", None) if "ROS_PACKAGE_PATH" not in env else None
    full["PYTHONPATH"] = os.pathsep.join(filter(None, [env.get("PYTHONPATH"), str(ROOT / "src")]))
    return subprocess.run(
        [sys.executable, "-c", code], cwd=cwd, env=full, capture_output=True, text=True
    )


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("ws")
    package = root / "src" / "my_interfaces"
    for kind in ("msg", "srv", "action"):
        (package / kind).mkdir(parents=True)
    (package / "package.xml").write_text("<package format='3'><name>my_interfaces</name></package>")
    (package / "msg" / "Num.msg").write_text("int64 num\nfloat64[] samples\n")
    (package / "srv" / "AddThree.srv").write_text("int64 a\nint64 b\nint64 c\n---\nint64 sum\n")
    (package / "action" / "Count.action").write_text("int32 to\n---\nint32[] seen\n---\nint32 at\n")
    return root


def test_workspace_interfaces_import_in_each_flavour(workspace: Path) -> None:
    rosidl = _run(
        "from my_interfaces.msg import Num\n"
        "from my_interfaces.srv import AddThree\n"
        "from my_interfaces.action import Count\n"
        "print(repr(Num(num=3, samples=[0.5])))\n"
        "print(repr(AddThree.Request(a=1)))\n"
        "print(repr(Count.Impl.FeedbackMessage().feedback))\n",
        workspace,
        ROBOMODEL_MESSAGE_FLAVOUR="rosidl",
    )
    assert rosidl.stdout.splitlines() == [
        "my_interfaces.msg.Num(num=3, samples=[0.5])",
        "my_interfaces.srv.AddThree_Request(a=1, b=0, c=0)",
        "my_interfaces.action.Count_Feedback(at=0)",
    ], rosidl.stderr
    genpy = _run(
        "from my_interfaces.srv import *\n"
        "print(AddThreeRequest(1, 2, 3).c, AddThree._request_class is AddThreeRequest)\n"
        "print(AddThreeResponse._type, len(AddThree._md5sum))\n"
        "from my_interfaces.msg import CountActionGoal, CountGoal\n"
        "print(type(CountActionGoal().goal) is CountGoal, CountActionGoal._type)\n",
        workspace,
        ROBOMODEL_MESSAGE_FLAVOUR="genpy",
    )
    assert genpy.stdout.split() == [
        "3",
        "True",
        "my_interfaces/AddThreeResponse",
        "32",
        "True",
        "my_interfaces/CountActionGoal",
    ], genpy.stderr


def test_a_source_folder_on_the_path_does_not_hide_the_interfaces(workspace: Path) -> None:
    """A script in the workspace's ``src/`` has that folder first on ``sys.path``, where the
    package's folders (no ``__init__.py``) import as empty namespace packages."""
    script = workspace / "src" / "uses_interfaces.py"
    script.write_text(
        "import my_interfaces\n"
        "from my_interfaces.srv import AddThree\n"
        "from my_interfaces.msg import Num\n"
        "print(AddThree.Request(a=2).a, Num(num=4).num, my_interfaces.__path__ is not None)\n"
    )
    ran = _run(
        f"import runpy; runpy.run_path({str(script)!r}, run_name='__main__')",
        workspace,
        PYTHONPATH=str(workspace / "src"),
    )
    assert ran.stdout.split() == ["2", "4", "True"], ran.stderr
    # a real module in the folder still wins over robomodel's
    real = workspace / "src" / "my_interfaces" / "msg" / "__init__.py"
    real.write_text("class Num:\n    REAL = True\n")
    try:
        won = _run(
            "from my_interfaces.msg import Num; print(Num.REAL)",
            workspace,
            PYTHONPATH=str(workspace / "src"),
        )
    finally:
        real.unlink()
    assert won.stdout.strip() == "True", won.stderr


def test_a_typo_names_the_close_package_and_where_robomodel_looked(workspace: Path) -> None:
    typo = _run("import my_interfacs.msg", workspace)
    assert typo.returncode == 1
    last = typo.stderr.strip().splitlines()[-1]
    assert last.startswith("ModuleNotFoundError: No module named 'my_interfacs'")
    assert "did you mean my_interfaces?" in last
    assert f"--package-path {workspace / 'src'}" in last and "noetic" in last
    unrelated = _run("import numpyy", workspace)
    assert (
        unrelated.stderr.strip().splitlines()[-1] == "ModuleNotFoundError: No module named 'numpyy'"
    )


def test_ros_package_path_package(workspace: Path, tmp_path: Path) -> None:
    found = _run(
        "from my_interfaces.msg import Num; print(Num.__typename__)",
        tmp_path,
        ROS_PACKAGE_PATH=str(workspace / "src"),
    )
    assert found.stdout.strip() == "my_interfaces/msg/Num", found.stderr


def test_a_real_installation_wins(tmp_path: Path) -> None:
    for name in ("rclpy", "std_msgs"):
        (tmp_path / "site" / name).mkdir(parents=True)
        (tmp_path / "site" / name / "__init__.py").write_text("REAL = True\n")
    (tmp_path / "site" / "std_msgs" / "msg.py").write_text("class String:\n    REAL = True\n")
    real = _run(
        "import rclpy, std_msgs.msg\n"
        "from std_msgs.msg import String\n"
        "print(rclpy.__file__)\nprint(std_msgs.msg.__file__)\nprint(String.REAL)\n",
        tmp_path,
        PYTHONPATH=str(tmp_path / "site"),
    )
    assert real.stdout.splitlines() == [
        str(tmp_path / "site" / "rclpy" / "__init__.py"),
        str(tmp_path / "site" / "std_msgs" / "msg.py"),
        "True",
    ], real.stderr


def test_the_finder_serves_imports_made_while_robomodel_s_resolver_loads() -> None:
    """In a venv of the wheel nothing imports pathlib before robomodel's message resolver
    does, and pathlib's ``from nt import ...`` reaches the finder while the resolver is only
    partly loaded. Here without ``site`` (the editable install's hooks import pathlib first),
    the finder installed as robomodel-clientlibs.pth installs it."""
    code = (
        f"import sys; sys.path.insert(0, {str(ROOT / 'src')!r})\n"
        f"exec(open({str(ROOT / 'src' / 'robomodel-clientlibs.pth')!r}).read())\n"
        "assert 'pathlib' not in sys.modules\n"
        "import robomodel.runtime.msg\n"
        "from std_msgs.msg import String\n"
        "print(repr(String(data='x')))\n"
    )
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "ROS_PACKAGE_PATH")}
    done = subprocess.run(
        [sys.executable, "-S", "-c", code], env=env, capture_output=True, text=True, cwd=ROOT
    )
    assert done.stdout.strip() == "std_msgs.msg.String(data='x')", done.stderr
