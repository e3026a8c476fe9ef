"""Start-up: which modules each command loads, so that it cannot silently regress.

Each command runs in a process of its own, through the same ``main`` as the console script,
and reports ``sys.modules`` when it is done. The time these imports take is measured by
``bench/bench_startup.py``; here only the set of modules is asserted (no timings).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import io
import os
import shutil
import subprocess
import sys
from pathlib import Path
from xml.sax.saxutils import quoteattr

import pytest
from hypothesis import given
from hypothesis import strategies as st

import robomodel
import robomodel.description as description
import robomodel.description.model as model
from robomodel.cli._parser import terminal_columns
from robomodel.cli._verbs import VERBS
from robomodel.cli.main import build_parser
from robomodel.description.urdf.writer import quote_attr

REPO = Path(__file__).resolve().parents[1]
EXAMPLES = REPO / "examples"
URDF = EXAMPLES / "two_link_arm" / "urdf" / "two_link_arm.urdf"
XACRO = EXAMPLES / "ur5_description" / "urdf" / "ur5_joint_limited_robot.urdf.xacro"

RUNNER = """
import sys
from robomodel.cli.main import main
try:
    main(sys.argv[2:])
except SystemExit:
    pass
finally:
    with open(sys.argv[1], "w") as out:
        out.write("\\n".join(sorted(sys.modules)))
"""

# Heavy or unrelated modules that none of the light commands may load.
NEVER_ON_LIGHT_PATHS = {
    "numpy",
    "yaml",
    "robomodel.kinematics",
    "robomodel.runtime",
    "robomodel.viewer",
    "robomodel.sim",
    "robomodel.control",
    "robomodel.launch",
    "robomodel.tf",
    "urllib.request",
    "http.client",
    "ssl",
    "email",
    "xml.sax.saxutils",
}


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env["ROBOMODEL_CLIENTLIBS"] = "0"  # the client-library finder's start is tested on its own
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(REPO / "src"), env.get("PYTHONPATH")]))
    return env


def _probe(code: str) -> subprocess.CompletedProcess[str]:
    """Run ``python -c code`` in the tests' environment, its output captured."""
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=_env())


def _baseline() -> set[str]:
    return set(_probe("import sys; print('\\n'.join(sys.modules))").stdout.split())


def modules_loaded_by(tmp_path: Path, *argv: str) -> set[str]:
    """The modules that ``robomodel ARGV`` loads beyond what the interpreter starts with."""
    report = tmp_path / "modules.txt"
    subprocess.run(
        [sys.executable, "-c", RUNNER, str(report), *argv],
        capture_output=True,
        env=_env(),
        cwd=tmp_path,
        check=False,
    )
    return set(report.read_text().split()) - _baseline()


def _offenders(loaded: set[str], banned: set[str]) -> list[str]:
    return sorted(
        m
        for m in loaded
        if m in banned or m.split(".")[0] in banned or any(m.startswith(b + ".") for b in banned)
    )


def _verb_modules(loaded: set[str]) -> set[str]:
    verbs = {verb.module for verb in VERBS}
    return {m for m in loaded if m in verbs}


def test_version_loads_only_the_entry_point(tmp_path: Path) -> None:
    loaded = modules_loaded_by(tmp_path, "--version")
    ours = {m for m in loaded if m.startswith("robomodel")}
    assert ours == {
        "robomodel",
        "robomodel._lazy",
        "robomodel._version",
        "robomodel.cli",
        "robomodel.cli._verbs",
        "robomodel.cli.main",
    }
    # Not even argparse and typing: --version should cost little more than starting Python.
    assert {"argparse", "typing", "dataclasses"}.isdisjoint(loaded)


def test_check_of_a_urdf_loads_neither_numpy_nor_xacro(tmp_path: Path) -> None:
    loaded = modules_loaded_by(tmp_path, "check", str(URDF))
    assert "robomodel.description.urdf.reader" in loaded  # it did run
    assert _offenders(loaded, NEVER_ON_LIGHT_PATHS | {"robomodel.xacro", "json"}) == []
    assert _verb_modules(loaded) == {"robomodel.cli.check"}
    assert "robomodel.description.urdf.writer" not in loaded


def test_check_of_a_xacro_loads_no_numpy(tmp_path: Path) -> None:
    loaded = modules_loaded_by(tmp_path, "check", str(XACRO))
    assert "robomodel.xacro" in loaded
    assert _offenders(loaded, NEVER_ON_LIGHT_PATHS) == []


def test_xacro_loads_no_urdf_model_and_no_typing(tmp_path: Path) -> None:
    loaded = modules_loaded_by(tmp_path, "xacro", str(XACRO))
    assert "robomodel.xacro._api" in loaded
    banned = NEVER_ON_LIGHT_PATHS | {
        "robomodel.description.model",
        "robomodel.description.urdf",
        "lxml",
        "typing",  # annotations only: guarded by TYPE_CHECKING on this path
        "tempfile",  # only for -o
        "shutil",  # argparse's formatter asks shutil for the width; ours does not
        "difflib",  # only when an error message suggests names
    }
    assert _offenders(loaded, banned) == []
    assert _verb_modules(loaded) == {"robomodel.cli.xacro"}


def test_graph_and_new_load_no_numpy(tmp_path: Path) -> None:
    graph = modules_loaded_by(tmp_path, "graph", str(URDF))
    assert "robomodel.description.report" in graph
    assert _offenders(graph, NEVER_ON_LIGHT_PATHS | {"robomodel.xacro"}) == []
    new = modules_loaded_by(tmp_path, "new", "thing_description", "--dir", str(tmp_path))
    assert (tmp_path / "thing_description" / "package.xml").exists()
    assert _offenders(new, NEVER_ON_LIGHT_PATHS) == []


def test_a_control_verb_without_a_robot_loads_no_description(tmp_path: Path) -> None:
    # `control run` reads a description; the parser offers its arguments, which must not
    # pull the description layer (lxml with it) into `control list-controllers`
    loaded = modules_loaded_by(tmp_path, "control", "list-controllers", "--help")
    assert "robomodel.cli.control" in loaded  # it did run
    banned = {"lxml", "robomodel.description", "robomodel.loading", "robomodel.xacro"}
    assert _offenders(loaded, banned) == []


def test_nodes_and_messages_load_no_yaml_until_yaml_is_read_or_written() -> None:
    """PyYAML (~20 ms) is for what reads or prints YAML (topic echo, params files), not for
    every bus verb: `control list-controllers` and a node publishing load none of it."""
    probe = (
        "import sys; from robomodel.runtime import Context; "
        "from robomodel.runtime.msg import JointState, message_to_yaml; "
        "import robomodel.runtime.transport.zenoh_bus; "
        "ctx = Context(); node = ctx.create_node('a'); "
        "node.create_publisher(JointState, '/js', 10).publish(JointState()); "
        "print('yaml' in sys.modules); message_to_yaml(JointState()); print('yaml' in sys.modules)"
    )
    out = _probe(probe)
    assert out.stdout.split() == ["False", "True"], out.stderr


@pytest.mark.process
def test_a_controller_manager_client_loads_no_controller() -> None:
    """The spawner and the ``controller_manager`` script only call a manager's services:
    ``robomodel.control.client`` loads no controller, hardware, manager or their config."""
    probe = (
        "import sys; from robomodel.control.client import ManagerClient; "
        "print('\\n'.join(m for m in sys.modules if m.startswith('robomodel.control')))"
    )
    out = _probe(probe)
    assert set(out.stdout.split()) == {"robomodel.control", "robomodel.control.client"}, (
        out.stdout + out.stderr
    )


@pytest.mark.process
def test_the_parameter_server_loads_no_launch_file_loader() -> None:
    """``robomodel run``, ``service`` and ``param`` on ROS 1 take the parameter server, which
    takes ``robomodel.launch.ros1.params`` alone: not the launch-file loader and its tags,
    whose names the package re-exports lazily (and gives the defining module's objects)."""
    probe = (
        "import sys, robomodel.launch.param_server, robomodel.launch.ros1 as ros1; "
        "print(sorted(m for m in sys.modules if m.startswith('robomodel.launch.ros1.'))); "
        "from robomodel.launch.ros1.loader import load_launch; "
        "print(ros1.load_launch is load_launch, 'load_launch' in dir(ros1))"
    )
    out = _probe(probe)
    assert out.stdout.splitlines() == [
        "['robomodel.launch.ros1.params']",
        "True True",
    ], out.stdout + out.stderr


@pytest.mark.process
def test_the_node_mappings_load_no_message_module_of_gazebo() -> None:
    """Every launch and ``robomodel run`` registers the node mappings; gazebo's services'
    types are loaded by the nodes that call them, when they run."""
    probe = (
        "import sys, robomodel.launch.nodes; "
        "print('robomodel.runtime.msg.types.gazebo_msgs' in sys.modules)"
    )
    out = _probe(probe)
    assert out.stdout.split() == ["False"], out.stdout + out.stderr


def test_help_imports_no_verb_module(tmp_path: Path) -> None:
    loaded = modules_loaded_by(tmp_path, "--help")
    assert _verb_modules(loaded) == set()


@pytest.mark.parametrize(
    "code",
    ["import robomodel", "import robomodel.description", "import robomodel.cli.main"],
)
def test_packages_load_no_sub_package_until_used(code: str) -> None:
    probe = (
        code
        + "; import sys; print('\\n'.join(m for m in sys.modules if m.startswith('robomodel')))"
    )
    out = _probe(probe)
    loaded = set(out.stdout.split())
    allowed = {
        "robomodel",
        "robomodel._lazy",
        "robomodel._version",
        "robomodel.description",
        "robomodel.cli",
        "robomodel.cli.main",
        "robomodel.cli._verbs",
    }
    assert loaded and loaded <= allowed, sorted(loaded - allowed)


def test_client_library_finder_loads_only_itself_at_start() -> None:
    env = dict(_env(), ROBOMODEL_CLIENTLIBS="1")
    probe = "import sys; print('\\n'.join(m for m in sys.modules if m.startswith('robomodel')))"
    site_start = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, env=env, check=True
    )
    loaded = set(site_start.stdout.split())
    hook = {
        "robomodel",
        "robomodel._lazy",
        "robomodel._version",
        "robomodel.clientlibs",
        "robomodel.clientlibs.hook",
        "robomodel.clientlibs.finder",
        "robomodel.clientlibs._workspace",
    }
    assert loaded == hook
    unrelated = "import sys\ntry:\n    import no_such_module_here\nexcept ImportError:\n    pass\n"
    after_miss = subprocess.run(
        [sys.executable, "-c", unrelated + probe[len("import sys; ") :]],
        capture_output=True,
        text=True,
        env=env,
        check=True,
    )
    assert set(after_miss.stdout.split()) == hook  # a failed import of another name costs no more


@pytest.mark.process
def test_the_message_package_loads_the_other_packages_types_on_first_use() -> None:
    """``robomodel.runtime.msg`` imports builtin_interfaces, std_msgs, geometry_msgs and
    rosgraph_msgs (every node's clock); the other classes it names come from their package's
    module when first used, and the listing of robomodel's types names them all the same."""
    probe = (
        "import sys; import robomodel.runtime.msg as msg\n"
        "types = 'robomodel.runtime.msg.types.'\n"
        "print(sorted(m[len(types):] for m in sys.modules if m.startswith(types)))\n"
        "from robomodel.runtime.msg.types.control_msgs import DynamicJointState\n"
        "print(msg.DynamicJointState is DynamicJointState, 'Odometry' in dir(msg))\n"
        "print('nav_msgs/msg/Odometry' in msg.message_type_names())\n"
    )
    out = _probe(probe)
    assert out.stdout.splitlines() == [
        "['builtin_interfaces', 'geometry_msgs', 'rosgraph_msgs', 'std_msgs']",
        "True True",
        "True",
    ], out.stderr


def test_lazy_names_are_the_defining_modules_objects() -> None:
    assert set(model.__all__) <= set(description.__all__)
    for name in model.__all__:
        assert getattr(description, name) is getattr(model, name)
    from robomodel.description.urdf.reader import read_urdf
    from robomodel.loading import load

    assert robomodel.read_urdf is read_urdf
    assert robomodel.load is load
    assert "Robot" in dir(robomodel)
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        _ = robomodel.nope  # type: ignore[attr-defined]
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        _ = description.nope  # type: ignore[attr-defined]
    from robomodel import control
    from robomodel.control.manager import ControllerManager

    assert control.ControllerManager is ControllerManager
    assert set(control.__all__) <= set(dir(control))


def _help(parser: argparse.ArgumentParser, argv: list[str]) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit):
        parser.parse_args(argv)
    return out.getvalue()


def test_one_verb_parser_gives_the_same_help_and_errors_as_all(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv("COLUMNS", "100")
    full = build_parser()
    assert _help(build_parser(""), ["--help"]) == _help(full, ["--help"])
    for verb in VERBS:
        assert _help(build_parser(verb.name), [verb.name, "--help"]) == _help(
            full, [verb.name, "--help"]
        )
    err_lazy, err_full = io.StringIO(), io.StringIO()
    for parser, err in ((build_parser(""), err_lazy), (full, err_full)):
        with contextlib.redirect_stderr(err), pytest.raises(SystemExit):
            parser.parse_args(["chekc"])
    assert "invalid choice: 'chekc'" in err_lazy.getvalue()
    assert err_lazy.getvalue() == err_full.getvalue()


def test_each_verb_module_registers_its_table_entry() -> None:
    for verb in VERBS:
        parser = argparse.ArgumentParser()
        subparsers = parser.add_subparsers()
        importlib.import_module(verb.module).register(subparsers)
        assert list(subparsers.choices) == [verb.name]
        assert [a.help for a in subparsers._choices_actions] == [verb.help]


def test_version_fast_path_prints_what_argparse_prints(tmp_path: Path) -> None:
    fast = subprocess.run(
        [sys.executable, "-m", "robomodel.cli.main", "--version"],
        capture_output=True,
        text=True,
        env=_env(),
    )
    slow = subprocess.run(
        [sys.executable, "-m", "robomodel.cli.main", "--debug", "--version"],
        capture_output=True,
        text=True,
        env=_env(),
    )
    assert fast.returncode == slow.returncode == 0
    assert fast.stdout == slow.stdout == f"robomodel {robomodel.__version__}\n"


@given(st.text(alphabet=st.sampled_from("ab&<>\"'\n\r\t é")))
def test_quote_attr_matches_saxutils(text: str) -> None:
    assert quote_attr(text) == quoteattr(text)


@pytest.mark.parametrize("columns", [None, "", "0", "-3", "x", "57", "200"])
def test_terminal_columns_matches_shutil(
    monkeypatch: pytest.MonkeyPatch, columns: str | None
) -> None:
    if columns is None:
        monkeypatch.delenv("COLUMNS", raising=False)
    else:
        monkeypatch.setenv("COLUMNS", columns)
    monkeypatch.setenv("LINES", "30")
    assert terminal_columns() == shutil.get_terminal_size().columns
