"""Substitutions, conditions, namespaces and parameter evaluation, transcribed from upstream tests."""

from __future__ import annotations

import pytest

from robomodel.description.packages import PackageIndex
from robomodel.launch.ros2.frontend.substitution_parser import parse_substitution
from robomodel.launch.ros2.shim.commands import PythonExpression
from robomodel.launch.ros2.shim.conditions import IfCondition
from robomodel.launch.ros2.shim.context import (
    LaunchContext,
    Session,
    SubstitutionFailure,
    session_scope,
)
from robomodel.launch.ros2.shim.logic import EqualsSubstitution, NotSubstitution
from robomodel.launch.ros2.shim.parameters import ParameterValue, evaluate_dict, normalize_dict
from robomodel.launch.ros2.shim.ros import prefix_namespace
from robomodel.launch.ros2.shim.substitutions import (
    LaunchConfiguration,
    PathJoinSubstitution,
    PathSubstitution,
    perform_substitutions,
)


@pytest.fixture
def context() -> LaunchContext:
    return LaunchContext(session=Session(packages=PackageIndex(use_environment=False)))


def test_prefix_namespace() -> None:
    """launch_ros utilities/namespace_utils.py docstring examples (and test_namespace_utils.py)."""
    assert prefix_namespace("my_ns", "original_ns") == "my_ns/original_ns"
    assert prefix_namespace("/my_ns", "original_ns") == "/my_ns/original_ns"
    assert prefix_namespace("my_ns", "/original_ns") == "/original_ns"
    assert prefix_namespace(None, "original_ns") == "original_ns"
    assert prefix_namespace("my_ns", None) == "my_ns"
    assert prefix_namespace("/", "a/") == "/a"


@pytest.mark.parametrize(
    ("left", "right", "expected"),
    [("a", "a", "true"), ("a", "b", "false"), ("1", "true", "true"), ("0", "False", "true"),
     ("1.0", "1", "true"), ("1e-9", "1.0e-9", "true"), ("true", "yes", "false")],
)  # fmt: skip
def test_equals_substitution(context: LaunchContext, left: str, right: str, expected: str) -> None:
    """launch test/launch/substitutions/test_equals_substitution.py: bools and floats."""
    assert EqualsSubstitution(left, right).perform(context) == expected


def test_conditions(context: LaunchContext) -> None:
    """launch test_if_condition.py: true/1/TRUE are true, false/0 false, others an error."""
    for text, value in (
        ("true", True),
        ("1", True),
        (" TRUE ", True),
        ("false", False),
        ("0", False),
    ):
        assert IfCondition(text).evaluate(context) is value
    with pytest.raises(SubstitutionFailure, match="Unexpected condition expression 'maybe'"):
        IfCondition("maybe").evaluate(context)
    assert NotSubstitution("false").perform(context) == "true"


def test_launch_configuration_default(context: LaunchContext) -> None:
    """launch test_launch_configuration.py: default used when unset, error without one."""
    assert LaunchConfiguration("x", default=["a", 1]).perform(context) == "a1"
    context.launch_configurations["x"] = "set"
    assert LaunchConfiguration("x", default="a").perform(context) == "set"
    with pytest.raises(SubstitutionFailure, match="launch configuration 'y' does not exist"):
        LaunchConfiguration("y").perform(context)


def test_python_expression(context: LaunchContext) -> None:
    """launch test_python_expression.py: math names direct and qualified; unsafe code refused."""
    assert PythonExpression(["2 * ", "pi > 6"]).perform(context) == "True"
    assert PythonExpression("math.floor(2.5)").perform(context) == "2"
    assert PythonExpression("'a' + 'b' == 'ab'").perform(context) == "True"
    with pytest.raises(SubstitutionFailure):
        PythonExpression("().__class__").perform(context)
    with pytest.raises(SubstitutionFailure, match="module 'os' is not available"):
        PythonExpression("1", ["os"]).perform(context)


def test_path_join_and_truediv(context: LaunchContext) -> None:
    """PathJoinSubstitution joins with os.path.join; ``/`` appends (Jazzy PathSubstitution)."""
    joined = PathSubstitution("/a") / "b" / LaunchConfiguration("f", default="c.txt")
    assert joined.perform(context) == "/a/b/c.txt"
    assert PathJoinSubstitution(["x", "/abs", "y"]).perform(context) == "/abs/y"


def test_parse_substitution(context: LaunchContext) -> None:
    """launch test/launch/frontend/test_substitutions.py: nesting, quotes, text around."""
    context.launch_configurations.update({"a": "b", "b": "final", "name": "x y"})
    assert (
        perform_substitutions(context, parse_substitution("pre $(var $(var a)) post"))
        == "pre final post"
    )
    assert perform_substitutions(context, parse_substitution("$(var nope 'x y')")) == "x y"
    assert perform_substitutions(context, parse_substitution("$(eval '1 + 2')")) == "3"
    assert perform_substitutions(context, parse_substitution("$(equals $(var a) b)")) == "true"
    assert perform_substitutions(context, parse_substitution("no subst")) == "no subst"


def test_parameter_yaml_rules(context: LaunchContext) -> None:
    """launch_ros test_normalize_parameters.py / test_evaluate_parameters.py."""
    with session_scope(context.session):
        normalized = normalize_dict(
            {"i": 1, "f": 1.5, "s": "1", "nested": {"b": True}, "ints": [1, 2], "mixed": [1, 2.0],
             "subst": LaunchConfiguration("v", default="3"), "text": ParameterValue("3", value_type=str)}
        )  # fmt: skip
        values = evaluate_dict(context, normalized)
    assert values == {
        "i": 1, "f": 1.5, "s": "1", "nested.b": True, "ints": (1, 2), "mixed": (1.0, 2.0),
        "subst": 3, "text": "3",
    }  # fmt: skip
    with pytest.raises(TypeError, match="Unable to parse the value of parameter bad as yaml"):
        evaluate_dict(context, normalize_dict({"bad": LaunchConfiguration("v", default="a: b: c")}))


def test_a_substituted_parameter_past_the_yaml_bounds_is_a_substitution_failure(
    context: LaunchContext,
) -> None:
    deep = LaunchConfiguration("v", default="[" * 500 + "]" * 500)
    refused = pytest.raises(SubstitutionFailure, match="parameter p: nested more than 100 levels")
    with refused, session_scope(context.session):
        evaluate_dict(context, normalize_dict({"p": deep}))
