"""Hostile input: any document made of xacro constructs either expands or raises InputError;
never another exception (no tracebacks for bad input)."""

from __future__ import annotations

import functools

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from robomodel import xacro as rx
from robomodel.errors import InputError

TAGS = [
    "xacro:property", "xacro:macro", "xacro:if", "xacro:unless", "xacro:insert_block",
    "xacro:include", "xacro:arg", "xacro:element", "xacro:attribute", "xacro:call", "xacro:m",
    "xacro:ns.m", "link", "a",
]  # fmt: skip
ATTRS = ["name", "value", "params", "default", "remove", "scope", "lazy_eval", "filename", "ns",
         "optional", "macro", "xacro:name", "a", "b"]  # fmt: skip
VALUES = st.one_of(
    st.sampled_from([
        "m", "a", "*b", "**b", "a:=1 *b", "a:=^", "a:=^|2", "b", "1", "0", "true", "parent",
        "global", "${a}", "${a+1}", "${", "}", "$(arg a)", "$(", "$(find x)", "$(eval 1+)",
        "${[1,2][5]}", "${'x'.y}", "${lambda: 0}", "${None}", "$$", "${1/0}", "x.xacro", "*.q",
        "${xacro.load_yaml('nope')}", "${m}", "${python.type(1)}", "a b c", "",
    ]),
    st.text(alphabet="ab$(){}:=^|*' 1.", max_size=12),
)  # fmt: skip


def _escape(value: str) -> str:
    return value.replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;")


_TAG = st.sampled_from(TAGS)
_NAMES = st.lists(st.sampled_from(ATTRS), max_size=3, unique=True)


@functools.cache
def _element(depth: int) -> st.SearchStrategy[str]:
    """Elements nested ``depth`` deep; one strategy object per depth, since building strategies
    during every draw costs hypothesis more than running the example."""
    children = st.lists(_element(depth - 1), max_size=3) if depth > 0 else st.just([])

    @st.composite
    def element(draw: st.DrawFn) -> str:
        tag = draw(_TAG)
        attrs = "".join(f' {n}="{_escape(draw(VALUES))}"' for n in draw(_NAMES))
        inner = "".join(draw(children))
        text = _escape(draw(VALUES)) if draw(st.booleans()) else ""
        return f"<{tag}{attrs}>{text}{inner}</{tag}>"

    return element()


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(_element(3), max_size=5))
def test_hostile_documents_raise_only_input_errors(elements: list[str]) -> None:
    text = '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">' + "".join(elements) + "</robot>"
    try:
        rx.process(text)
    except InputError as exc:
        assert exc.line is None or exc.line >= 1
