"""One or more tests per language feature: byte-identical with the reference, and the value
that feature must produce (so that a shared mistake cannot pass)."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel import xacro as rx
from tests.xacro.conftest import assert_same, doc

# (feature, document body, mappings, text the output must contain)
CASES: list[tuple[str, str, dict[str, str], str]] = [
    ("property-number", '<xacro:property name="a" value="2"/><x v="${a*3}"/>', {}, 'v="6"'),
    (
        "property-float",
        '<xacro:property name="a" value="0.1"/><x v="${a*3}"/>',
        {},
        'v="0.30000000000000004"',
    ),
    (
        "property-lazy-forward-ref",
        '<xacro:property name="a" value="${b+1}"/><xacro:property name="b" value="1"/><x v="${a}"/>',
        {},
        'v="2"',
    ),
    (
        "property-greedy",
        '<xacro:property name="a" value="x"/><xacro:property name="a" value="${a.upper()}" lazy_eval="false"/><x v="${a}"/>',
        {},
        'v="X"',
    ),
    (
        "property-quoted-string",
        '<xacro:property name="a" value="\'abc\'"/><x v="${a+\'2\'}"/>',
        {},
        'v="abc2"',
    ),
    (
        "property-underscore-stays-string",
        '<xacro:property name="a" value="1_000"/><x v="${a+\'x\'}"/>',
        {},
        'v="1_000x"',
    ),
    ("property-bool", '<xacro:property name="a" value="true"/><x v="${a and 1}"/>', {}, 'v="1"'),
    ("property-default-unset", '<xacro:property name="a" default="5"/><x v="${a}"/>', {}, 'v="5"'),
    (
        "property-default-set",
        '<xacro:property name="a" value="1"/><xacro:property name="a" default="5"/><x v="${a}"/>',
        {},
        'v="1"',
    ),
    (
        "property-remove",
        '<xacro:property name="a" value="1"/><xacro:property name="a" remove="true"/><x v="${\'a\' in python.dir() if False else 2}"/>',
        {},
        'v="2"',
    ),
    (
        "property-scope-global",
        '<xacro:macro name="m"><xacro:property name="g" value="7" scope="global"/></xacro:macro><xacro:m/><x v="${g}"/>',
        {},
        'v="7"',
    ),
    (
        "property-scope-parent",
        '<xacro:macro name="m"><xacro:property name="g" value="8" scope="parent"/></xacro:macro><xacro:m/><x v="${g}"/>',
        {},
        'v="8"',
    ),
    (
        "block-property",
        '<xacro:property name="blk"><a/><b/></xacro:property><x><xacro:insert_block name="blk"/></x>',
        {},
        "<a/>",
    ),
    (
        "macro-params",
        '<xacro:macro name="m" params="a b"><x v="${a}-${b}"/></xacro:macro><xacro:m a="1" b="q"/>',
        {},
        'v="1-q"',
    ),
    (
        "macro-default",
        '<xacro:macro name="m" params="a:=3 b=4"><x v="${a+b}"/></xacro:macro><xacro:m/>',
        {},
        'v="7"',
    ),
    (
        "macro-default-quoted",
        '<xacro:macro name="m" params="a:=\'x y\'"><x v="${a}"/></xacro:macro><xacro:m/>',
        {},
        'v="x y"',
    ),
    (
        "macro-forward",
        '<xacro:property name="a" value="9"/><xacro:macro name="m" params="a:=^"><x v="${a}"/></xacro:macro><xacro:m/>',
        {},
        'v="9"',
    ),
    (
        "macro-forward-default",
        '<xacro:macro name="m" params="a:=^|5"><x v="${a}"/></xacro:macro><xacro:m/>',
        {},
        'v="5"',
    ),
    (
        "macro-block",
        '<xacro:macro name="m" params="*b"><w><xacro:insert_block name="b"/></w></xacro:macro><xacro:m><origin xyz="1"/></xacro:m>',
        {},
        '<origin xyz="1"/>',
    ),
    (
        "macro-multiblock",
        '<xacro:macro name="m" params="**b"><w><xacro:insert_block name="b"/></w></xacro:macro><xacro:m><c><d/><e/></c></xacro:m>',
        {},
        "<d/>",
    ),
    (
        "macro-block-twice",
        '<xacro:macro name="m" params="*b"><xacro:insert_block name="b"/><xacro:insert_block name="b"/></xacro:macro><xacro:m><o/></xacro:m>',
        {},
        "<o/>\n  <o/>",
    ),
    (
        "macro-typed-arg",
        '<xacro:macro name="m" params="l"><x v="${l[1]}"/></xacro:macro><xacro:m l="${[1, 2]}"/>',
        {},
        'v="2"',
    ),
    (
        "macro-recursion",
        '<xacro:macro name="r" params="n"><i v="${n}"/><xacro:if value="${n}"><xacro:r n="${n-1}"/></xacro:if></xacro:macro><xacro:r n="3"/>',
        {},
        'v="0"',
    ),
    (
        "macro-nested-definition",
        '<xacro:macro name="o"><xacro:macro name="i"><in/></xacro:macro><xacro:i/></xacro:macro><xacro:o/>',
        {},
        "<in/>",
    ),
    (
        "macro-dynamic-scope",
        '<xacro:macro name="inner"><x v="${p}"/></xacro:macro><xacro:macro name="outer" params="p"><xacro:inner/></xacro:macro><xacro:outer p="5"/>',
        {},
        'v="5"',
    ),
    (
        "macro-call",
        '<xacro:macro name="m" params="a"><x v="${a}"/></xacro:macro><xacro:call macro="${\'m\'}" a="3"/>',
        {},
        'v="3"',
    ),
    (
        "macro-redefinition",
        '<xacro:macro name="m"><one/></xacro:macro><xacro:m/><xacro:macro name="m"><two/></xacro:macro><xacro:m/>',
        {},
        "<one/>\n  <two/>",
    ),
    (
        "macro-default-in-caller-scope",
        '<xacro:property name="d" value="1"/><xacro:macro name="m" params="a:=${d}"><x v="${a}"/></xacro:macro><xacro:property name="d" value="2"/><xacro:m/>',
        {},
        'v="2"',
    ),
    (
        "if-true",
        '<xacro:if value="true"><a/></xacro:if><xacro:if value="0"><b/></xacro:if>',
        {},
        "<a/>",
    ),
    (
        "if-expression",
        '<xacro:if value="${3*0.1}"><a/></xacro:if><xacro:if value="${[]}"><b/></xacro:if>',
        {},
        "<a/>",
    ),
    (
        "unless",
        '<xacro:unless value="false"><a/></xacro:unless><xacro:unless value="1"><b/></xacro:unless>',
        {},
        "<a/>",
    ),
    ("arg-default", '<xacro:arg name="n" default="d"/><x v="$(arg n)"/>', {}, 'v="d"'),
    ("arg-mapping", '<xacro:arg name="n" default="d"/><x v="$(arg n)"/>', {"n": "cli"}, 'v="cli"'),
    (
        "arg-function",
        '<xacro:arg name="n" default="5"/><x v="${xacro.arg(\'n\') * 2}"/>',
        {},
        'v="55"',
    ),
    (
        "element",
        '<xacro:property name="t" value="joint"/><xacro:element xacro:name="${t}" name="j"/>',
        {},
        '<joint name="j"/>',
    ),
    ("attribute", "<x><xacro:attribute name=\"${'a'+'b'}\" value=\"v\"/></x>", {}, 'ab="v"'),
    ("target-namespace", "<a/>", {}, "<a/>"),
    ("xacro-attributes-removed", '<x xacro:foo="1" y="2"/>', {}, '<x y="2"/>'),
    (
        "math",
        '<x v="${pi} ${math.sqrt(4)} ${radians(180)} ${floor(2.5)}"/>',
        {},
        'v="3.141592653589793 2.0 3.141592653589793 2"',
    ),
    ("python-namespace", '<x v="${python.sum([1, 2])} ${python.sorted([2, 1])}"/>', {}, "3 [1, 2]"),
    (
        "comprehension-lambda",
        '<x v="${[i*i for i in range(3)]} ${(lambda q: q+1)(1)}"/>',
        {},
        'v="[0, 1, 4] 2"',
    ),
    (
        "str-methods",
        "<x v=\"${'a,b'.split(',')} ${'x'.upper()} ${dict(a=1).items()}\"/>",
        {},
        "['a', 'b'] X",
    ),
    ("tokenize", "<x v=\"${xacro.tokenize('a b;c')}\"/>", {}, "['a', 'b', 'c']"),
    ("dotify", '<x v="${xacro.dotify(dict(a=1)).a}"/>', {}, 'v="1"'),
    (
        "numbers-str",
        '<x v="${1e20} ${1e-7} ${2.0} ${1/3} ${True}"/>',
        {},
        'v="1e+20 1e-07 2.0 0.3333333333333333 True"',
    ),
    ("eval-ext", '<x v="$(eval 1+2)"/>', {}, 'v="3"'),
    ("eval-ext-arg", '<xacro:arg name="a" default="2"/><x v="$(eval a * 2)"/>', {}, 'v="4"'),
    (
        "optenv",
        '<x v="$(optenv ROBOMODEL_SURELY_UNSET_VAR fallback words)"/>',
        {},
        'v="fallback words"',
    ),
    (
        "arg-in-expr",
        '<xacro:arg name="var" default="ab"/><x v="${2*\'$(arg var)\'}"/>',
        {},
        'v="abab"',
    ),
    (
        "expr-in-arg",
        '<xacro:arg name="var" default="ab"/><x v="$(arg ${\'v\'+\'ar\'})"/>',
        {},
        'v="ab"',
    ),
    ("dollar-escape", '<x v="$${a} $$(b) $$$${c} a$ $ $x"/>', {}, 'v="${a} $(b) $$${c} a$ $ $x"'),
    ("text-eval", "<x> a ${1+1} b </x>", {}, "<x> a 2 b </x>"),
    ("cdata-untouched", "<x><![CDATA[ ${nope} ]]></x>", {}, "<![CDATA[ ${nope} ]]>"),
    ("comments-kept", "<!-- keep --><x/>", {}, "<!-- keep -->"),
    (
        "comments-removed-before-tags",
        '<!-- gone --><xacro:property name="a" value="1"/><x/>',
        {},
        "<x/>",
    ),
    (
        "eval-comments",
        '<xacro:property name="a" value="1"/><!-- xacro:eval-comments --><!-- a=${a} --><x/><!-- b=${a} -->',
        {},
        "<!-- a=1 -->",
    ),
    (
        "mixed-text-layout",
        '<xacro:property name="w" value="1"/><x>t ${w}<b/> tail</x>',
        {},
        "    t 1\n",
    ),
    (
        "escaping",
        '<x v="&lt;&amp;&quot;&gt;">a &lt; b &amp; "c" &gt;</x>',
        {},
        'v="&lt;&amp;&quot;&gt;"',
    ),
    ("attr-newline-normalisation", '<x v="a\nb"/>', {}, 'v="a b"'),
    ("empty-text-inline", "<x>${''}</x>", {}, "<x></x>"),
    ("whitespace-only-inline", "<x>   </x>", {}, "<x>   </x>"),
    ("unicode", "<x v=\"${'ä'*2}\">ü</x>", {}, 'v="ää"'),
]


@pytest.mark.parametrize(
    ("body", "mappings", "expected"), [c[1:] for c in CASES], ids=[c[0] for c in CASES]
)
def test_feature_matches_reference(body: str, mappings: dict[str, str], expected: str) -> None:
    output = assert_same(doc(body), mappings)
    assert expected in output


def test_call_does_not_warn_about_its_arguments(tmp_path: Path) -> None:
    path = tmp_path / "c.xacro"
    path.write_text(
        doc(
            '<xacro:macro name="m" params="a"><x v="${a}"/></xacro:macro><xacro:call macro="m" a="1"/>'
        )
    )
    result = rx.process_file(path)
    assert result.warnings == ()
    assert '<x v="1"/>' in result.toprettyxml()


def test_target_namespace_becomes_xmlns() -> None:
    text = '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" xacro:targetNamespace="urn:t"><a/></robot>'
    assert '<robot xmlns="urn:t">' in assert_same(text)


def test_root_attributes_are_evaluated_before_args() -> None:
    # Real packages depend on this order (the reference evaluates root attributes first).
    text = '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="$(arg n)"><xacro:arg name="n" default="d"/></robot>'
    assert 'name="given"' in assert_same(text, {"n": "given"})


def test_namespaced_include(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "inc.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" xmlns:foo="urn:foo">'
        '<xacro:property name="p" value="4"/><xacro:macro name="m"><m v="${p}"/></xacro:macro>'
        "<included/></robot>"
    )
    body = '<xacro:include filename="inc.xacro" ns="A"/><x v="${A.p}"/><xacro:A.m/>'
    output = assert_same(doc(body))
    assert 'v="4"' in output and "<included/>" in output and 'xmlns:foo="urn:foo"' in output


def test_include_glob_and_optional(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    for name in ("b", "a"):
        (tmp_path / f"{name}.xacro").write_text(f"<r><{name}/></r>")
    body = '<xacro:include filename="*.xacro"/><xacro:include filename="missing.xacro" optional="true"/>'
    output = assert_same(doc(body))
    assert output.index("<a/>") < output.index("<b/>")


def test_include_in_false_if_is_lazy() -> None:
    assert_same(doc('<xacro:if value="0"><xacro:include filename="nope.xacro"/></xacro:if><x/>'))
