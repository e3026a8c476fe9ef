"""Bounds of the parameter server and of YAML from users and peers."""

from __future__ import annotations

import json
import logging
import subprocess
from pathlib import Path

import pytest
import yaml

from robomodel._yaml_bounded import YamlNestingError, load_yaml
from robomodel.launch.param_server import SERVICE, ParamServer
from robomodel.runtime import Context
from robomodel.runtime.msg.types.robomodel_interfaces import MasterCall, MasterCall_Request
from robomodel.runtime.transport.ros1.param_bounds import (
    DICT_BYTES,
    ParamBoundError,
    expand_bounded,
    tree_size,
)
from robomodel.runtime.transport.ros1.param_tree import ParamServerError, ParamTree
from tests.conftest import ROBOMODEL
from tests.timing import scaled

# 9 levels of 10 aliases each: 10**9 leaves once expanded, a few hundred bytes as text
LAUGHS = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n" + "".join(
    f"a{i}: &a{i} [*a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}, "
    f"*a{i - 1}, *a{i - 1}, *a{i - 1}, *a{i - 1}]\n"
    for i in range(1, 9)
)


def test_aliases_are_expanded_apart_once() -> None:
    shared = [1, 2]
    tree = expand_bounded({"a": shared, "b": shared, 3: ("x",)})
    assert tree == {"a": [1, 2], "b": [1, 2], "3": ["x"]}
    assert tree["a"] is not tree["b"]  # a get costs what the stored tree costs
    dict_bytes = DICT_BYTES  # what one dictionary costs besides its entries
    assert tree_size(tree) == dict_bytes + 8 + 1 + (8 + 16) + 8 + 1 + (8 + 16) + 8 + 1 + (8 + 1)


def test_a_billion_laughs_is_refused_when_set() -> None:
    bomb = yaml.safe_load(LAUGHS)  # loads fine: shared references
    tree = ParamTree()
    with pytest.raises(ParamServerError, match="larger than 32 MiB once expanded"):
        tree.set("/bomb", bomb)
    assert not tree.has("/bomb")


def test_one_value_and_the_whole_tree_are_bounded() -> None:
    tree = ParamTree(max_value_bytes=1000, max_tree_bytes=2500)
    with pytest.raises(ParamServerError, match=r"\[/big\] is larger than"):
        tree.set("/big", "x" * 1001)
    tree.set("/a", "x" * 900)
    tree.set("/b", "x" * 900)
    with pytest.raises(ParamServerError, match="more than 0 MiB; delete parameters first"):
        tree.set("/c", "x" * 900)
    tree.set("/a", "x" * 10)  # overwriting gives the room back
    tree.set("/c", "x" * 900)
    tree.delete("/b")
    tree.set("/d", "x" * 800)
    assert sorted(tree.names()) == ["/a", "/c", "/d"]


def test_nesting_is_bounded() -> None:
    deep: list[object] = []
    for _ in range(150):
        deep = [deep]
    with pytest.raises(ParamBoundError, match="nested deeper than 100 levels"):
        expand_bounded(deep)


def test_the_servers_refusal_reaches_the_client_over_the_bus() -> None:
    server = ParamServer(max_value_bytes=100)
    with Context("inproc") as context:
        server.serve(context)
        big = MasterCall_Request("setParam", json.dumps({"key": "/x", "value": "y" * 200}))
        reply = context.call_service(SERVICE, MasterCall, big)
        assert not reply.ok and "[/x] is larger than 0 MiB" in reply.error
        nested = MasterCall_Request("getParam", "[" * 100_000 + "]" * 100_000)
        reply = context.call_service(SERVICE, MasterCall, nested)
        assert not reply.ok and reply.error == "arguments are nested too deeply"


def test_a_failing_service_logs_one_line_and_answers(caplog: pytest.LogCaptureFixture) -> None:
    from robomodel.runtime.msg.types.std_srvs import Trigger

    def handler(request: object) -> object:
        return json.loads("[" * 100_000 + "]" * 100_000)  # RecursionError

    with Context("inproc") as context, caplog.at_level(logging.WARNING):
        node = context.create_node("n")
        node.create_service(Trigger, "/deep", handler)
        with pytest.raises(Exception, match="service '/deep' failed: maximum recursion depth"):
            context.call_service("/deep", Trigger)
    lines = [r for r in caplog.records if "/deep" in r.getMessage()]
    assert len(lines) == 1 and lines[0].exc_info is None
    assert "RecursionError" in lines[0].getMessage()


def test_deep_yaml_is_a_clear_error() -> None:
    assert load_yaml("[1, [2]]") == [1, [2]]
    with pytest.raises(YamlNestingError, match="nested too deeply"):
        load_yaml("[" * 3000 + "]" * 3000)
    with pytest.raises(YamlNestingError, match="once expanded"):
        load_yaml(LAUGHS)


@pytest.mark.parametrize(
    "argv",
    [
        ["param", "set", "/x", "[" * 3000 + "]" * 3000, "--bus", "inproc"],
        [
            "topic",
            "pub",
            "-1",
            "/x",
            "std_msgs/msg/String",
            "{data: " + "[" * 3000,
            "--bus",
            "inproc",
        ],
    ],
)
def test_cli_deep_yaml_exits_2_without_traceback(argv: list[str]) -> None:
    argv = [a if not a.endswith("[" * 3000) else a + "]" * 3000 + "}" for a in argv]
    done = subprocess.run([*ROBOMODEL, *argv], capture_output=True, text=True, timeout=scaled(60))
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert "nested too deeply" in done.stderr


def test_an_alias_bomb_in_a_launch_file_is_refused_at_load(tmp_path: Path) -> None:
    bomb = tmp_path / "laughs.yaml"
    bomb.write_text(LAUGHS)
    path = tmp_path / "laughs.launch"
    path.write_text(f'<launch>\n  <rosparam file="{bomb}" param="bomb"/>\n</launch>\n')
    done = subprocess.run(
        [*ROBOMODEL, "launch", str(path), "--dump-params"],
        capture_output=True,
        text=True,
        timeout=scaled(60),
    )
    assert done.returncode == 2 and "Traceback" not in done.stderr
    # Placed in the YAML file, where the bound is passed, and in the launch file that reads it.
    assert f"{bomb}:6:" in done.stderr and f"included from {path}:2:" in done.stderr
    assert "once its aliases are expanded" in done.stderr
