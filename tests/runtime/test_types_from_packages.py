"""Types of the user's interface packages (msg/ and srv/ files on the package path) and types
robomodel has no class for, through the verbs in separate processes on the Zenoh bus: topic
pub/echo/info/hz and service call."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml

from robomodel.runtime.msg import (
    MessageTypeError,
    _resolver,
    get_message_type,
    message_from_yaml,
    serialize,
)
from robomodel.runtime.msg.schema import get_service_type
from robomodel.runtime.msg.typehash import type_hash
from tests.conftest import ROBOMODEL, unique_domain
from tests.timing import scaled

IMAGE = (
    "{height: 2, width: 2, encoding: rgb8, step: 6, data: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12]}"
)


def make_package(root: Path) -> Path:
    """``my_msgs`` with a message that uses another of its own, a common one and a
    constant, and a service."""
    package = root / "my_msgs"
    (package / "msg").mkdir(parents=True)
    (package / "srv").mkdir()
    (package / "package.xml").write_text(
        '<package format="3"><name>my_msgs</name><version>0.0.0</version></package>'
    )
    (package / "msg" / "Reading.msg").write_text(
        "uint8 KIND_PRESSURE=1\nstd_msgs/Header header\nfloat64 value\nstring unit\n"
        "int16[3] raw\nCalibration[] calibrations\n"
    )
    (package / "msg" / "Calibration.msg").write_text("string name\nfloat32 gain\n")
    (package / "srv" / "Scale.srv").write_text(
        "float64 value\nfloat64 factor\n---\nfloat64 result\n"
    )
    return root


@pytest.fixture
def packages(tmp_path: Path) -> Iterator[Path]:
    root = make_package(tmp_path / "ws")
    _resolver.configure(package_paths=(root,))
    yield root
    _resolver.configure(package_paths=())


def test_package_message_and_service(packages: Path) -> None:
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    reading = get_message_type("my_msgs/Reading")
    assert reading.KIND_PRESSURE == 1  # type: ignore[attr-defined]
    msg = message_from_yaml(
        reading, "{value: 2.5, unit: bar, raw: [1, -2, 3], calibrations: [{name: a, gain: 2.0}]}"
    )
    store = get_typestore(Stores.ROS2_JAZZY)
    for name in ("Reading", "Calibration"):
        text = (packages / "my_msgs" / "msg" / f"{name}.msg").read_text()
        store.register(get_types_from_msg(text, f"my_msgs/msg/{name}"))
    theirs = store.deserialize_cdr(serialize(msg), "my_msgs/msg/Reading")
    assert (theirs.value, theirs.unit, theirs.raw.tolist()) == (2.5, "bar", [1, -2, 3])
    assert theirs.calibrations[0].gain == 2.0
    assert type_hash(reading) == store.hash_rihs01("my_msgs/msg/Reading")
    scale = get_service_type("my_msgs/srv/Scale")
    assert scale.Request.field_names() == ("value", "factor")
    assert scale.Response.field_names() == ("result",)
    with pytest.raises(MessageTypeError, match=f"--package-path {packages}"):
        get_message_type("my_msgs/msg/Missing")


def test_learned_definition_resolves_what_nothing_else_has() -> None:
    text = "geometry_msgs/Point where\nuint8 level\n" + "=" * 80 + "\nMSG: geometry_msgs/Point\n"
    text += "float64 x\nfloat64 y\nfloat64 z\n"
    with pytest.raises(MessageTypeError):
        get_message_type("lab_msgs/msg/Probe")
    _resolver.learn_definition("lab_msgs/Probe", text)
    probe = get_message_type("lab_msgs/msg/Probe")
    assert probe.field_names() == ("where", "level")
    assert probe.__fields__[0][1] is get_message_type("geometry_msgs/msg/Point")  # hand-written


GENMSG = textwrap.dedent(
    """
    import json, os, sys
    import genmsg, genmsg.msg_loader as loader
    from std_msgs.msg import Header
    root, scratch = sys.argv[1], sys.argv[2]
    os.makedirs(os.path.join(scratch, "std_msgs", "msg"))
    with open(os.path.join(scratch, "std_msgs", "msg", "Header.msg"), "w") as out:
        out.write(Header._full_text)
    search = {"my_msgs": [os.path.join(root, "my_msgs", "msg")],
              "std_msgs": [os.path.join(scratch, "std_msgs", "msg")]}
    ctx = genmsg.MsgContext.create_default()
    reading = loader.load_msg_by_type(ctx, "my_msgs/Reading", search)
    loader.load_depends(ctx, reading, search)
    scale = loader.load_srv_from_file(
        ctx, os.path.join(root, "my_msgs", "srv", "Scale.srv"), "my_msgs/Scale")
    loader.load_depends(ctx, scale, search)
    print(json.dumps([genmsg.compute_md5(ctx, reading), genmsg.compute_md5(ctx, scale)]))
    """
)


def test_ros1_types_follow_the_package_folders_set_now(tmp_path: Path) -> None:
    """A package's type as ROS 1 sees it (md5sum, definition, service md5sum) is the one of
    the folders set now, not of folders set before: two workspaces with a ``Reading`` and a
    ``Scale`` of their own, one after the other in one process."""
    import hashlib

    from robomodel.runtime.transport.ros1.ros1_types import (
        ros1_service_type,
        ros1_type,
        ros1_type_named,
    )

    def workspace(name: str, reading: str, scale: str) -> Path:
        package = tmp_path / name / "md5_msgs"
        (package / "msg").mkdir(parents=True)
        (package / "srv").mkdir()
        (package / "package.xml").write_text(
            '<package format="3"><name>md5_msgs</name><version>0.0.0</version></package>'
        )
        (package / "msg" / "Reading.msg").write_text(reading + "\n")
        (package / "srv" / "Scale.srv").write_text(scale)
        return tmp_path / name

    def md5(text: str) -> str:
        return hashlib.md5(text.encode()).hexdigest()

    first = workspace("first", "float64 value", "float64 value\n---\nfloat64 result\n")
    second = workspace("second", "string unit", "int32 a\n---\nint32 b\n")
    try:
        for root, reading, scale in ((first, "float64 value", ("float64 value", "float64 result")),
                                     (second, "string unit", ("int32 a", "int32 b"))):  # fmt: skip
            _resolver.configure(package_paths=(root,))
            found = ros1_type(get_message_type("md5_msgs/msg/Reading"))
            assert (found.md5sum, found.definition.strip()) == (md5(reading), reading)
            assert ros1_type_named("md5_msgs/Reading").md5sum == md5(reading)
            service = ros1_service_type(get_service_type("md5_msgs/srv/Scale"))
            assert service.md5sum == md5("".join(scale))  # genmsg: request's then response's
    finally:
        _resolver.configure(package_paths=())


def test_ros1_md5sums_of_package_types_equal_genmsg(packages: Path, tmp_path: Path) -> None:
    """ROS 1's md5sums of a package's message and service, as Debian's genmsg computes them."""
    import json

    from robomodel.runtime.transport.ros1.ros1_types import ros1_service_type, ros1_type

    done = subprocess.run(
        ["/usr/bin/python3", "-c", GENMSG, str(packages), str(tmp_path / "scratch")],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-500:]
    reading_md5, scale_md5 = json.loads(done.stdout)
    assert ros1_type(get_message_type("my_msgs/msg/Reading")).md5sum == reading_md5
    assert ros1_service_type(get_service_type("my_msgs/srv/Scale")).md5sum == scale_md5


SERVER = textwrap.dedent(
    """
    import sys
    from robomodel.runtime import Context
    from robomodel.runtime.msg.schema import get_service_type
    Scale = get_service_type("my_msgs/srv/Scale")
    ctx = Context("zenoh", domain_id=int(sys.argv[1]))
    node = ctx.create_node("scaler")
    node.create_service(Scale, "/scale", lambda req: Scale.Response(req.value * req.factor))
    print("ready", flush=True)
    ctx.spin()
    """
)


def _run(env: dict[str, str], *argv: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [*ROBOMODEL, *argv], capture_output=True, text=True, timeout=scaled(90), env=env
    )


def test_verbs_across_processes(tmp_path: Path) -> None:
    root = make_package(tmp_path / "ws")
    env = {**os.environ, "ROS_PACKAGE_PATH": str(root)}
    domain = unique_domain()
    bus = ("--domain-id", domain)
    procs = []
    try:
        for topic, kind, value in (
            ("/img", "sensor_msgs/msg/Image", IMAGE),
            ("/reading", "my_msgs/msg/Reading", "{value: 2.5, unit: bar, raw: [1, -2, 3]}"),
        ):
            procs.append(subprocess.Popen(
                [*ROBOMODEL, "topic", "pub", topic, kind, value, "-r", "10", *bus], env=env,
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, text=True,
            ))  # fmt: skip
        script = tmp_path / "server.py"
        script.write_text(SERVER)
        server = subprocess.Popen(
            [sys.executable, str(script), domain], env=env, stdout=subprocess.PIPE, text=True
        )
        procs.append(server)
        assert server.stdout is not None and server.stdout.readline().strip() == "ready"
        image = _run(env, "topic", "echo", "/img", "--once", *bus)
        assert image.returncode == 0, image.stderr
        got = yaml.safe_load(image.stdout.split("---")[0])
        assert (got["encoding"], got["data"]) == ("rgb8", list(range(1, 13)))
        reading = _run(env, "topic", "echo", "/reading", "--once", *bus)
        assert reading.returncode == 0, reading.stderr
        got = yaml.safe_load(reading.stdout.split("---")[0])
        assert (got["value"], got["unit"], got["raw"]) == (2.5, "bar", [1, -2, 3])
        info = _run(env, "topic", "info", "/reading", *bus)
        assert "Type: my_msgs/msg/Reading" in info.stdout, info.stderr
        hz = _run(env, "topic", "hz", "/img", "--duration", "3", *bus)
        assert hz.returncode == 0 and "average rate" in hz.stdout, hz.stderr
        call = _run(env, "service", "call", "/scale", "my_msgs/srv/Scale",
                    "{value: 2.5, factor: 4.0}", "--timeout", f"{scaled(30):.1f}", *bus)  # fmt: skip
        assert call.returncode == 0, call.stderr
        assert "response (" in call.stdout and call.stdout.endswith("result: 10.0\n")
    finally:
        for proc in procs:
            proc.kill()
            proc.wait()


def test_ament_prefix_path_packages(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An installed ROS 2 package: <prefix>/share/<pkg>/msg/*.msg, found by AMENT_PREFIX_PATH."""
    make_package(tmp_path / "prefix" / "share")
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(tmp_path / "prefix"))
    _resolver.configure()
    try:
        assert get_message_type("my_msgs/msg/Calibration").field_names() == ("name", "gain")
    finally:
        monkeypatch.delenv("AMENT_PREFIX_PATH")
        _resolver.configure()


def test_distro_option_of_the_verbs() -> None:
    """``--distro humble``: Humble's sensor_msgs/msg/Range, which has no ``variance``."""
    argv = ("topic", "pub", "/range", "sensor_msgs/msg/Range", "{variance: 0.5}", "--once")
    humble = subprocess.run(
        [*ROBOMODEL, *argv, "--bus", "inproc", "--distro", "humble"],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip
    assert humble.returncode == 2 and "has no field 'variance'" in humble.stderr
    assert "Traceback" not in humble.stderr
    jazzy = subprocess.run(
        [*ROBOMODEL, *argv, "--bus", "inproc", "--distro", "jazzy"],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip
    assert jazzy.returncode == 0 and "variance=0.5" in jazzy.stdout, jazzy.stderr


def test_a_publishers_other_hash_is_named(tmp_path: Path) -> None:
    """A publisher of Humble's sensor_msgs/msg/Range (no ``variance``: another RIHS01 hash) on
    a Jazzy bus and robomodel's Jazzy echo: one warning line naming both hashes (rmw_zenoh
    keeps them apart). (A Humble bus, ROS_DISTRO=humble, carries no hashes at all.)"""
    from rosbags.typesys import Stores, get_typestore

    domain = unique_domain()
    env = {k: v for k, v in os.environ.items() if k != "ROS_DISTRO"}  # a Jazzy bus (hashes)
    pub = subprocess.Popen(
        [*ROBOMODEL, "topic", "pub", "/range", "sensor_msgs/msg/Range", "{range: 1.5}",
         "-r", "10", "--domain-id", domain, "--distro", "humble"],
        env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, text=True,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + scaled(60)
        while "/range" not in _run(env, "topic", "list", "--domain-id", domain).stdout:
            assert time.monotonic() < deadline, "the publisher did not appear in 60 s"
        # (the echo gets nothing, the hashes differ: 3 s is its time to see the publisher)
        echo = subprocess.run(
            [*ROBOMODEL, "topic", "echo", "/range", "--once", "--timeout", f"{scaled(3):.1f}",
             "--domain-id", domain, "--distro", "jazzy"],
            capture_output=True, text=True, timeout=scaled(90), env=env,
        )  # fmt: skip
    finally:
        pub.kill()
        pub.wait()
    humble = get_typestore(Stores.ROS2_HUMBLE).hash_rihs01("sensor_msgs/msg/Range")
    jazzy = get_typestore(Stores.ROS2_JAZZY).hash_rihs01("sensor_msgs/msg/Range")
    warnings = [line for line in echo.stderr.splitlines() if line.startswith("warning: /range")]
    assert len(warnings) == 1, echo.stderr
    assert humble in warnings[0] and jazzy in warnings[0]


def test_a_later_different_definition_is_refused_with_one_warning(
    caplog: pytest.LogCaptureFixture,
) -> None:
    """The first definition learned of a name stays: classes built from it may be in use."""
    _resolver.learn_definition("lab_msgs/Twice", "float64 first\n")
    kind = get_message_type("lab_msgs/msg/Twice")
    with caplog.at_level("WARNING", logger="robomodel.msg"):
        _resolver.learn_definition("lab_msgs/Twice", "string other\n")
        _resolver.learn_definition("lab_msgs/Twice", "string other\n")
        _resolver.learn_definition("lab_msgs/Twice", "float64 first\n")  # the same: no warning
    warnings = [r.getMessage() for r in caplog.records if "lab_msgs/msg/Twice" in r.getMessage()]
    assert len(warnings) == 1 and "earlier one stays" in warnings[0], warnings
    assert get_message_type("lab_msgs/msg/Twice") is kind
    assert kind.field_names() == ("first",)
