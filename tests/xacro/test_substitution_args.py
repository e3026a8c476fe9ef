"""The ``$(...)`` engine xacro and ROS 1 launch files share, through its public API.

Both dialects' outputs are checked against the references elsewhere (tests/xacro against xacro
2.1.1, tests/launch against roslaunch); these tests pin what the two dialects do differently,
so that neither side takes on the other's rules.
"""

from __future__ import annotations

import importlib

import pytest

from robomodel.launch.ros1.substitution import SubstitutionContext, resolve
from robomodel.xacro import substitution_args as sa
from robomodel.xacro.substitution_args import (
    ROSLAUNCH,
    XACRO,
    ArgNotSet,
    SubstitutionError,
    SubstitutionScope,
    resolve_args,
    safe_evaluator,
)


def _scope(**kwargs: object) -> SubstitutionScope:
    base: dict[str, object] = {
        "args": {"robot": "ur5", "n": "2", "where": "$(find ur5_description)"},
        "find": lambda name: f"/pkgs/{name}",
        "environ": {"HOME": "/home/me"},
        "evaluate": safe_evaluator(),
    }
    base.update(kwargs)
    return SubstitutionScope(**base)  # type: ignore[arg-type]


def test_every_public_name_resolves() -> None:
    module = importlib.import_module("robomodel.xacro.substitution_args")
    for name in module.__all__:
        assert getattr(module, name) is not None, name


@pytest.mark.parametrize("dialect", [XACRO, ROSLAUNCH])
def test_both_dialects_resolve_the_common_commands(dialect: sa.Dialect) -> None:
    text = "$(arg where)/$(env HOME)/$(optenv NOPE a b)/$(dirname)"
    resolved = resolve_args(text, _scope(filename="/w/r.xacro"), dialect)
    assert resolved == "/pkgs/ur5_description//home/me/a b//w"
    assert resolve_args("$(eval n * 3 + arg('n'))", _scope(), dialect) == "8"


def test_anon_is_roslaunchs_only() -> None:
    names = iter(("a_1", "a_2"))
    scope = _scope(anon=lambda name: next(names))
    assert resolve_args("$(anon a)", scope, ROSLAUNCH) == "a_1"
    with pytest.raises(SubstitutionError, match=r"^unknown substitution command \[anon a\]"):
        resolve_args("$(anon a)", scope, XACRO)
    with pytest.raises(SubstitutionError, match=r"Valid commands are \['find', 'env', "):
        resolve_args("$(nope a)", scope, ROSLAUNCH)


def _missing(name: str) -> str:
    raise SubstitutionError(f"package '{name}' not found")


def test_roslaunch_finds_packages_after_everything_else() -> None:
    """roslaunch's second pass is for ``find`` alone; robomodel's xacro finds in both."""
    text = "$(find nope) $(arg unset)"
    with pytest.raises(ArgNotSet):
        resolve_args(text, _scope(find=_missing), ROSLAUNCH)
    with pytest.raises(SubstitutionError, match="package 'nope' not found"):
        resolve_args(text, _scope(find=_missing), XACRO)


def test_an_unset_arg_names_the_set_ones_in_each_dialects_words() -> None:
    with pytest.raises(ArgNotSet) as launch:
        resolve_args("$(arg robo)", _scope(), ROSLAUNCH)
    assert str(launch.value) == (
        "arg 'robo' is not set; did you mean 'robot'? (set args: n, robot, where)"
    )
    assert launch.value.name == "robo" and sorted(launch.value.known) == ["n", "robot", "where"]
    with pytest.raises(ArgNotSet) as xacro:
        resolve_args("$(arg robo)", _scope(), XACRO)
    assert str(xacro.value).startswith("undefined substitution argument 'robo'; did you mean")
    assert '<xacro:arg name="robo" default="..."/>' in str(xacro.value)


def test_the_launch_side_keeps_its_bounds_and_anon_names() -> None:
    ctx = SubstitutionContext({"x": "1"}, lambda name: name, {})
    first = resolve("$(anon talker)", ctx)
    assert first is not None and first.startswith("talker_")
    assert resolve("$(anon talker) $(anon talker)", ctx) == f"{first} {first}"
    with pytest.raises(SubstitutionError, match="double underscore"):
        resolve("$(eval x.__class__)", ctx)
    with pytest.raises(ArgNotSet, match=r"^arg 'y' is not set"):
        resolve("$(eval y + 1)", ctx)
    assert resolve("$(eval pi > 3)", ctx) == "True"
