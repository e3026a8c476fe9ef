"""The expansion walk: ``eval_all`` and the tag handlers (reference L902-L1000).

The walk is the reference's, step for step, because its order of evaluation and its tree edits
determine the output bytes: attributes first, then the children in document order, each
``xacro:`` tag replaced in place by its expansion.
"""

from __future__ import annotations

from collections.abc import Callable

from robomodel.xacro._calls import handle_macro_call, process_include
from robomodel.xacro._context import Context
from robomodel.xacro._definitions import grab_macro, grab_property
from robomodel.xacro._dom import Comment, Document, Element, Text
from robomodel.xacro._evaluation import eval_text
from robomodel.xacro._nodeops import (
    check_attrs,
    remove_previous_comments,
    replace_node,
)
from robomodel.xacro._symbols import BooleanError, Scope, to_boolean

__all__ = ["eval_all", "process_document"]

Handler = Callable[[Context, Element, Scope, Scope], bool]


def _insert_block(ctx: Context, node: Element, macros: Scope, symbols: Scope) -> bool:
    (name,) = check_attrs(ctx, node, ["name"], [])
    if "**" + str(name) in symbols:
        block, content_only = symbols.lookup("**" + str(name)), True
    elif "*" + str(name) in symbols:
        block, content_only = symbols.lookup("*" + str(name)), False
    else:
        raise ctx.error(f'Undefined block "{name}"', node, "name")
    if not isinstance(block, Element):
        raise ctx.error(f'"{name}" is not a block', node, "name")
    counter = [0]
    copy = block.clone(counter)
    ctx.charge_nodes(counter[0])
    eval_all(ctx, copy, macros, symbols)
    ctx.charge_work(replace_node(node, copy, content_only=content_only))
    return False


def _include(ctx: Context, node: Element, macros: Scope, symbols: Scope) -> bool:
    process_include(ctx, node, macros, symbols, eval_all)
    return False


def _property(ctx: Context, node: Element, macros: Scope, symbols: Scope) -> bool:
    grab_property(ctx, node, symbols)
    return False


def _macro(ctx: Context, node: Element, macros: Scope, symbols: Scope) -> bool:
    grab_macro(ctx, node, macros)
    return False


def _arg(ctx: Context, node: Element, macros: Scope, symbols: Scope) -> bool:
    name, default = check_attrs(ctx, node, ["name", "default"], [])
    if name is not None:
        ctx.declared_args.add(name)
    if name is not None and name not in ctx.args:
        ctx.node, ctx.attr = node, "default"
        ctx.args[name] = str(eval_text(ctx, default or "", symbols))
    remove_previous_comments(ctx, node)
    replace_node(node, None)
    return False


def _element(ctx: Context, node: Element, macros: Scope, symbols: Scope) -> bool:
    spec = node.attrs.get("xacro:name")
    if spec is None:
        raise ctx.error("xacro:element: missing attribute 'xacro:name'", node)
    ctx.node, ctx.attr = node, "xacro:name"
    name = eval_text(ctx, spec, symbols)
    if not name:
        raise ctx.error("xacro:element: empty name", node, "xacro:name")
    del node.attrs["xacro:name"]
    node.tag = str(name)
    return True  # process the renamed element again


def _attribute(ctx: Context, node: Element, macros: Scope, symbols: Scope) -> bool:
    values = []
    for attr in ("name", "value"):
        text = node.attrs.get(attr)
        if text is None:
            raise ctx.error(f"xacro:attribute: missing attribute '{attr}'", node)
        ctx.node, ctx.attr = node, attr
        values.append(eval_text(ctx, text, symbols))
    if not values[0]:
        raise ctx.error("xacro:attribute: empty name", node, "name")
    if isinstance(node.parent, Element):
        # str(): the reference crashes on non-string values (AttributeError on .replace).
        node.parent.attrs[str(values[0])] = str(values[1])
    replace_node(node, None)
    return False


def _conditional(ctx: Context, node: Element, macros: Scope, symbols: Scope) -> bool:
    remove_previous_comments(ctx, node)
    (cond,) = check_attrs(ctx, node, ["value"], [])
    ctx.node, ctx.attr = node, "value"
    try:
        keep = to_boolean(eval_text(ctx, cond or "", symbols), cond)
    except BooleanError as exc:
        raise ctx.error(str(exc), node, "value") from None
    if node.tag == "xacro:unless":
        keep = not keep
    if keep:
        eval_all(ctx, node, macros, symbols)
        ctx.charge_work(replace_node(node, node, content_only=True))
    else:
        replace_node(node, None)
    return False


def _call(ctx: Context, node: Element, macros: Scope, symbols: Scope) -> bool:
    handle_macro_call(ctx, node, macros, symbols, eval_all)
    return False


_HANDLERS: dict[str, Handler] = {
    "xacro:insert_block": _insert_block,
    "xacro:include": _include,
    "xacro:property": _property,
    "xacro:macro": _macro,
    "xacro:arg": _arg,
    "xacro:element": _element,
    "xacro:attribute": _attribute,
    "xacro:if": _conditional,
    "xacro:unless": _conditional,
}


def _eval_attributes(ctx: Context, node: Element, symbols: Scope) -> None:
    attrs = node.attrs
    if "xacro:" in " ".join(attrs):  # rare: xacro:* attributes are dropped
        for name in [name for name in attrs if name.startswith("xacro:")]:
            del attrs[name]
    for name, value in attrs.items():  # replacing values while iterating is safe
        if "$" in value:
            ctx.node, ctx.attr = node, name
            attrs[name] = str(eval_text(ctx, value, symbols))
    attrs.pop("xmlns:xacro", None)


def eval_all(ctx: Context, node: Element, macros: Scope, symbols: Scope) -> None:
    """Evaluate ``node`` in place: attributes, then children, expanding every xacro tag."""
    if node.attrs:
        _eval_attributes(ctx, node, symbols)
    child = node.first
    eval_comments = False
    while child is not None:
        following = child.next
        kind = type(child)
        if kind is Element:
            eval_comments = False
            tag = child.tag  # type: ignore[attr-defined]
            if tag.startswith("xacro:"):
                handler = _HANDLERS.get(tag, _call)
                if handler(ctx, child, macros, symbols):  # type: ignore[arg-type]
                    continue
            else:
                eval_all(ctx, child, macros, symbols)  # type: ignore[arg-type]
        elif kind is Text:
            data: str = child.data  # type: ignore[attr-defined]
            if "$" in data:
                ctx.node, ctx.attr = child, None
                data = child.data = str(eval_text(ctx, data, symbols))  # type: ignore[attr-defined]
            if data.strip():
                eval_comments = False
        elif kind is Comment:
            data = child.data  # type: ignore[attr-defined]
            if "xacro:eval-comments" in data:
                eval_comments = "xacro:eval-comments:off" not in data
                replace_node(child, None)
            elif eval_comments and "$" in data:
                ctx.node, ctx.attr = child, None
                child.data = str(eval_text(ctx, data, symbols))  # type: ignore[attr-defined]
        child = following


def process_document(ctx: Context, document: Document) -> None:
    """Expand ``document`` in place (reference ``process_doc``, L1044)."""
    macros = Scope(None, {})
    symbols = Scope(None, ctx.globals, lambda raw, scope: eval_text(ctx, raw, scope))
    root = document.root
    target = root.attrs.get("xacro:targetNamespace")
    if target:
        del root.attrs["xacro:targetNamespace"]
        root.attrs["xmlns"] = target
    eval_all(ctx, root, macros, symbols)
