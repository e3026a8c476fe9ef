"""Exponential expansions are refused by a bound on total work, not after minutes.

A macro that calls itself twice per level does 2^depth calls; before the work bound only the
node limit stopped it (2^20 after 44 s). Each case here must be refused with the work message,
at the expanding node, with the macro stack, while the work counted at refusal stays at the
bound (so the time to refuse is that of ``Limits.max_work`` units, whatever the depth).
"""

from __future__ import annotations

import importlib.util
import subprocess
from pathlib import Path

import pytest

from robomodel import xacro as rx
from robomodel.description.packages import PackageIndex
from robomodel.errors import InputError
from robomodel.xacro._context import Context
from tests.conftest import ROBOMODEL
from tests.xacro.conftest import EXAMPLES, REPO, doc

FAN_OUT = (
    '<xacro:macro name="f" params="n">'
    '<xacro:if value="${n &gt; 0}"><xacro:f n="${n-1}"/><xacro:f n="${n-1}"/></xacro:if>'
    '<xacro:unless value="${n &gt; 0}"><link name="l"/></xacro:unless>'
    "</xacro:macro>"
    '<xacro:f n="{depth}"/>'
)


def _work_used(monkeypatch: pytest.MonkeyPatch) -> list[Context]:
    contexts: list[Context] = []
    original = Context.__post_init__

    def remember(self: Context) -> None:
        original(self)
        contexts.append(self)

    monkeypatch.setattr(Context, "__post_init__", remember)
    return contexts


# The default bound at depth 30; a tenth of it at the other depths, which shows the same
# (refused at the bound, whatever the depth) in a tenth of the time.
_TENTH = rx.Limits(max_work=rx.Limits().max_work // 10)


@pytest.mark.parametrize(
    ("depth", "limits"),
    [(12, _TENTH), (14, _TENTH), (16, _TENTH), (20, _TENTH), (30, rx.Limits())],
    ids=["12-tenth", "14-tenth", "16-tenth", "20-tenth", "30-default"],
)
def test_exponential_macro_fan_out_is_refused_by_work(
    depth: int, limits: rx.Limits, monkeypatch: pytest.MonkeyPatch
) -> None:
    contexts = _work_used(monkeypatch)
    with pytest.raises(InputError, match="units of work") as info:
        rx.process(doc(FAN_OUT.replace("{depth}", str(depth))), limits=limits)
    assert info.value.line == 1 and info.value.column is not None
    assert sum("in macro 'f'" in note.message for note in info.value.notes) >= 3
    # Refused at the bound: the work done does not depend on the depth asked for.
    assert -limits.max_work // 50 < contexts[-1].work_left <= 0
    assert contexts[-1].nodes_left > limits.max_nodes - limits.max_work


def test_fan_out_small_enough_still_expands() -> None:
    out = rx.process(doc(FAN_OUT.replace("{depth}", "8")))
    assert out.count('<link name="l"/>') == 2**8


def test_string_doubling_through_text_is_bounded() -> None:
    # "${p}${p}" joins text pieces (no operator of the evaluator sees the length).
    props = '<xacro:property name="p0" value="ab"/>' + "".join(
        f'<xacro:property name="p{i}" value="${{p{i - 1}}}${{p{i - 1}}}"/>' for i in range(1, 40)
    )
    with pytest.raises(InputError, match=r"longer than|units of work"):
        rx.process(doc(props + '<x v="${p39}"/>'))


def test_eval_string_doubling_is_bounded() -> None:
    # $(eval) sees xacro args: each arg's default doubles the previous one.
    args = '<xacro:arg name="a0" default="ab"/>' + "".join(
        f'<xacro:arg name="a{i}" default="$(eval a{i - 1} + a{i - 1})"/>' for i in range(1, 40)
    )
    with pytest.raises(InputError, match=r"longer than|units of work"):
        rx.process(doc(args + '<x v="$(arg a39)"/>'))


def _synthetic_pr2(tmp_path: Path) -> tuple[Path, PackageIndex]:
    spec = importlib.util.spec_from_file_location("bench_xacro", REPO / "bench" / "bench_xacro.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    top = module.write_synthetic_robot(tmp_path)
    return top, PackageIndex(package_paths=[tmp_path], use_environment=False)


def test_real_sized_robots_stay_far_inside_the_bound(tmp_path: Path) -> None:
    # A tenth of the default bound is enough for a PR2-size robot and every example.
    small = rx.Limits(max_work=rx.Limits().max_work // 10)
    top, index = _synthetic_pr2(tmp_path)
    assert rx.expand(top, package_index=index, limits=small).text.count("<link ") >= 80
    examples = PackageIndex(package_paths=[EXAMPLES], use_environment=False)
    for path in sorted(EXAMPLES.glob("*/urdf/*.xacro")):
        if path.name.endswith((".urdf.xacro", "rrbot.xacro")):
            rx.expand(path, package_index=examples, limits=small)


def test_cli_refuses_with_exit_2_and_the_stack(tmp_path: Path) -> None:
    path = tmp_path / "fan.xacro"
    path.write_text(doc(FAN_OUT.replace("{depth}", "30")))
    run = subprocess.run([*ROBOMODEL, "xacro", str(path)], capture_output=True, text=True)
    assert run.returncode == 2
    first, *notes = run.stderr.splitlines()
    assert first.startswith(f"{path}:1:") and "units of work" in first
    assert any("in macro 'f'" in note for note in notes)
    assert run.stdout == ""
