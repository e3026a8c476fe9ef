"""robomodel's typed message modules are what tools/gen_msgs.py generates from the types'
definitions (rosbags' Jazzy store, runtime/msg/interfaces/), and stay so."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

from robomodel.runtime.msg import Quaternion, Time, get_message_type
from robomodel.runtime.msg._resolver import _distro_store
from robomodel.runtime.msg.typehash import type_hash
from robomodel.runtime.msg.types.unique_identifier_msgs import UUID
from tests.timing import scaled

ROOT = Path(__file__).resolve().parents[2]
MSG = ROOT / "src" / "robomodel" / "runtime" / "msg"
sys.path.insert(0, str(ROOT / "tools"))
from gen_msgs_modules import MODULES, ROS1_ONLY  # noqa: E402


def _check(*argv: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, str(ROOT / "tools" / "gen_msgs.py"), "--check", *argv],
                          capture_output=True, text=True, timeout=scaled(300), cwd=ROOT)  # fmt: skip


def test_checked_in_modules_are_the_generators_output() -> None:
    done = _check()
    assert done.returncode == 0, f"run python tools/gen_msgs.py:\n{done.stdout}{done.stderr}"


def test_check_names_a_module_that_differs(tmp_path: Path) -> None:
    for folder in ("types", "layouts"):
        shutil.copytree(MSG / folder, tmp_path / folder)
    edited = tmp_path / "types" / "geometry_msgs.py"
    edited.write_text(edited.read_text().replace("w: float = 1.0", "w: float = 0.0"))
    (tmp_path / "types" / "std_srvs.py").unlink()
    done = _check("--out", str(tmp_path))
    assert done.returncode == 1
    assert sorted(line.rsplit("/", 1)[-1] for line in done.stdout.splitlines()) == [
        "geometry_msgs.py",
        "std_srvs.py",
    ]


def test_generated_classes_keep_helpers_and_defaults() -> None:
    """What a definition does not say: Quaternion's default w (Quaternion.msg's ``w 1``, which
    rosbags' store drops) and the helpers mixed in."""
    assert Quaternion() == Quaternion(0.0, 0.0, 0.0, 1.0)
    assert Time.from_seconds(1.25) == Time(1, 250_000_000)
    assert Time(2, 5).to_nanoseconds() == 2_000_000_005
    assert len(UUID.random().uuid) == 16 and UUID.random() != UUID.random()


def test_generated_store_types_hash_as_rosbags() -> None:
    store = _distro_store()
    keys = [k for _, names in MODULES.values() for k in names if k not in ROS1_ONLY]
    # rosbags hashes char as char, rosidl as uint8 (test_type_hashes documents it)
    in_store = [
        k for k in keys if k in store.fielddefs and k != "service_msgs/msg/ServiceEventInfo"
    ]
    assert len(in_store) > 40
    for key in in_store:
        assert type_hash(get_message_type(key)) == store.hash_rihs01(key), key


def test_one_module_per_ros_package() -> None:
    """Every generated class lives in the module named as its ROS package, every generated
    module is one of MODULES, and a type is found by name with no table naming its module."""
    import importlib

    generated = {p.stem for p in (MSG / "types").glob("*.py")} - {"__init__"}
    assert generated == set(MODULES)
    for package in sorted(generated):
        module = importlib.import_module(f"robomodel.runtime.msg.types.{package}")
        for name in module.__all__:
            assert getattr(module, name).__typename__.split("/")[0] == package, name
    for key in (
        "tf2_msgs/msg/TFMessage",
        "rosgraph_msgs/msg/Clock",
        "unique_identifier_msgs/msg/UUID",
    ):
        assert (
            get_message_type(key).__module__ == f"robomodel.runtime.msg.types.{key.split('/')[0]}"
        )


def test_earlier_layouts_are_not_registered() -> None:
    """The generated ControllerState of ros2_control 4.0-4.12 is named as the type but the
    registry keeps the current layout (with is_async and update_rate, 4.28 on)."""
    from robomodel.runtime.msg.layouts.controller_manager_msgs import ControllerState_4_0

    current = get_message_type("controller_manager_msgs/msg/ControllerState")
    assert ControllerState_4_0.__typename__ == current.__typename__
    assert current is not ControllerState_4_0
    assert "is_async" in current.field_names()
    assert "exported_state_interfaces" not in ControllerState_4_0.field_names()
