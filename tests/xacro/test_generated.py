"""Documents generated from a grammar of the xacro constructs: our bytes equal the reference's,
and where the reference fails we fail too (with an InputError, never a crash)."""

from __future__ import annotations

import functools
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from robomodel import xacro as rx
from robomodel.errors import InputError
from tests.xacro.conftest import reference_file, reference_text

PROPS = ("p0", "p1", "p2")
NUMBERS = st.sampled_from(["0", "1", "2", "3", "0.5", "1.25", "-2", "1e-3", "10"])
WORDS = st.sampled_from(
    ["a", "link", "x y", " spaced ", "&amp;", "&lt;b&gt;", "q&quot;", "$$x", "$", "a$b"]
)


@functools.cache
def _expr(names: tuple[str, ...]) -> st.SearchStrategy[str]:
    atoms = st.one_of(NUMBERS, st.sampled_from(names) if names else NUMBERS, st.just("'s'"))
    return st.recursive(
        atoms,
        lambda inner: st.one_of(
            st.tuples(inner, st.sampled_from([" + ", " - ", " * ", " / ", "*"]), inner).map(
                "".join
            ),
            inner.map(lambda e: f"({e})"),
            st.tuples(inner, st.sampled_from([" &lt; ", " == ", " &gt;= "]), inner).map("".join),
            inner.map(lambda e: f"-{e}"),
        ),
        max_leaves=4,
    )


@functools.cache
def _value(names: tuple[str, ...]) -> st.SearchStrategy[str]:
    expr = _expr(names).map(lambda e: "${" + e + "}")
    return st.one_of(
        NUMBERS, WORDS, expr, st.sampled_from(["true", "false", "'quoted'"]),
        st.tuples(WORDS, expr, WORDS).map("".join),
    )  # fmt: skip


@functools.cache
def _text() -> st.SearchStrategy[str]:
    return st.one_of(
        st.sampled_from(["\n  ", "\n\n  ", " ", "\n"]),
        st.tuples(st.sampled_from(["", "\n    "]), WORDS, st.sampled_from(["", "\n  "])).map(
            "".join
        ),
    )


# One strategy object per argument tuple: building strategies during every draw costs
# hypothesis more than running the example.
@functools.cache
@st.composite
def _content(
    draw: st.DrawFn, names: tuple[str, ...], macros: tuple[str, ...], depth: int, blocks: bool
) -> str:
    items: list[str] = []
    for _ in range(draw(st.integers(1 if depth > 1 else 0, 5))):
        kind = draw(
            st.sampled_from(
                ["element", "text", "comment", "if", "call", "property", "cdata", "block"]
            )
        )
        if kind == "element":
            tag = draw(st.sampled_from(["a", "link", "joint"]))
            attrs = "".join(
                f' {k}="{draw(_value(names))}"'
                for k in draw(st.sets(st.sampled_from(["name", "xyz", "v"]), max_size=2))
            )
            inner = draw(_content(names, macros, depth - 1, blocks)) if depth > 0 else ""
            items.append(
                f"<{tag}{attrs}>{inner}</{tag}>"
                if inner or draw(st.booleans())
                else f"<{tag}{attrs}/>"
            )
        elif kind == "text":
            items.append(draw(_text()))
        elif kind == "comment":
            items.append(
                f"<!-- {draw(st.sampled_from(['note', 'c ${p0}', 'xacro:eval-comments', 'x']))} -->"
            )
        elif kind == "if" and depth > 0:
            tag = draw(st.sampled_from(["if", "unless"]))
            cond = draw(st.sampled_from(["true", "false", "1", "0", "${p0 &gt; 1}", "${1 == 1}"]))
            items.append(
                f'<xacro:{tag} value="{cond}">{draw(_content(names, macros, depth - 1, blocks))}</xacro:{tag}>'
            )
        elif kind == "call" and macros:
            macro = draw(st.sampled_from(macros))
            args = f' a="{draw(_value(names))}"' + (
                f' b="{draw(_value(names))}"' if draw(st.booleans()) else ""
            )
            block = "<blk/>" if macro.endswith("b") else ""
            items.append(f"<xacro:{macro}{args}>{block}</xacro:{macro}>")
        elif kind == "property":
            items.append(
                f'<xacro:property name="{draw(st.sampled_from(PROPS))}" value="{draw(_value(names))}"/>'
            )
        elif kind == "cdata":
            items.append("<![CDATA[ raw ${p0} ]]>")
        elif kind == "block" and blocks:
            items.append('<xacro:insert_block name="blk"/>')
    return "".join(items)


@st.composite
def documents(draw: st.DrawFn) -> str:
    parts = [
        f'<xacro:property name="{p}" value="{draw(_value(()))}"/>{draw(_text())}' for p in PROPS[:2]
    ]
    macros: list[str] = []
    for i in range(draw(st.integers(0, 2))):
        with_block = draw(st.booleans())
        name = f"m{i}{'b' if with_block else ''}"
        params = "a b:=2" + (" *blk" if with_block else "")
        body = draw(_content(("a", "b", *PROPS[:2]), tuple(macros), 2, with_block))
        parts.append(
            f'<xacro:macro name="{name}" params="{params}">{body}</xacro:macro>{draw(_text())}'
        )
        macros.append(name)
    parts.append(draw(_content(PROPS, tuple(macros), 3, False)))
    return '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">' + "".join(parts) + "</robot>"


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(documents())
def test_generated_documents_are_byte_identical(text: str) -> None:
    try:
        expected = reference_text(text)
    except Exception:  # the reference fails: so must we, cleanly
        with pytest.raises(InputError):
            rx.process(text)
        return
    assert rx.process(text) == expected


@st.composite
def include_trees(draw: st.DrawFn) -> tuple[str, str, str]:
    """A main file and two included files, with and without namespaces."""
    inner_ns, main_ns = draw(st.booleans()), draw(st.booleans())
    q = "In.q" if inner_ns else "q"
    leaf = "In.leaf" if inner_ns else "leaf"
    inner = (
        f'<xacro:property name="q" value="{draw(NUMBERS)}"/>'
        '<xacro:macro name="leaf" params="a b:=1"><leaf v="${a}" w="${b}"/></xacro:macro>'
        f"{draw(_content(('q',), ('leaf',), 2, False))}"
    )
    middle = (
        '<xacro:include filename="inner.xacro"'
        + (' ns="In"' if inner_ns else "")
        + "/>"
        + draw(st.sampled_from(["", f'<mid v="${{{q}}}"/>', f'<xacro:{leaf} a="${{{q}*2}}"/>']))
        + '<xacro:macro name="mid" params="a"><m v="${a}"/></xacro:macro>'
    )
    prefix = "M." if main_ns else ""
    main = (
        '<xacro:include filename="sub/middle.xacro"'
        + (' ns="M"' if main_ns else "")
        + "/>"
        + draw(_text())
        + f'<xacro:{prefix}mid a="{draw(_value(()))}"/>'
        + draw(
            st.sampled_from(["", f'<x v="${{{prefix}{q}}}"/>', f'<xacro:{prefix}{leaf} a="3"/>'])
        )
        + draw(st.sampled_from(["", "<!-- c -->", "\n  <!-- c -->\n  <y/>"]))
    )
    wrap = '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">{}</robot>'.format
    return wrap(main), wrap(middle), wrap(inner)


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(include_trees())
def test_generated_include_trees_are_byte_identical(files: tuple[str, str, str]) -> None:
    main, middle, inner = files
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        (root / "sub").mkdir()
        (root / "main.xacro").write_text(main)
        (root / "sub" / "middle.xacro").write_text(middle)
        (root / "sub" / "inner.xacro").write_text(inner)
        try:
            expected = reference_file(root / "main.xacro")
        except Exception:  # the reference fails: so must we, cleanly
            with pytest.raises(InputError):
                rx.process_file(root / "main.xacro")
            return
        assert rx.process_file(root / "main.xacro").toprettyxml(indent="  ") == expected
