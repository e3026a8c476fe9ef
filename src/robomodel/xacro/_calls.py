"""Macro calls and includes (reference ``handle_macro_call`` L780, ``process_include`` L508)."""

from __future__ import annotations

import glob
import os
import re
from collections.abc import Callable

from robomodel._files import UserFileError, read_user_bytes
from robomodel.errors import close_matches
from robomodel.xacro._context import Context, Frame
from robomodel.xacro._definitions import Macro
from robomodel.xacro._dom import Document, Element, next_element
from robomodel.xacro._evaluation import abs_filename_spec, eval_text
from robomodel.xacro._nodeops import (
    check_attrs,
    remove_previous_comments,
    replace_node,
)
from robomodel.xacro._parse import parse_xml
from robomodel.xacro._symbols import BooleanError, Scope, to_boolean

__all__ = ["handle_macro_call", "import_xml_namespaces", "process_include", "read_document"]

EvalAll = Callable[[Context, Element, Scope, Scope], None]


def _resolve_macro(name: str, macros: Scope, symbols: Scope) -> tuple[Scope, Scope, Macro]:
    def walk(namespaces: list[str], short: str) -> tuple[Scope, Scope, Macro]:
        m_scope, s_scope = macros, symbols
        for ns in namespaces:
            m_next, s_next = m_scope.lookup(ns), s_scope.lookup(ns)
            if not isinstance(m_next, Scope) or not isinstance(s_next, Scope):
                raise KeyError(ns)
            m_scope, s_scope = m_next, s_next
        macro = m_scope.lookup(short)
        if not isinstance(macro, Macro):
            raise KeyError(short)
        return m_scope, s_scope, macro

    try:
        return walk([], name)
    except KeyError:
        namespaces = name.split(".")
        short = namespaces.pop()
        if not namespaces:
            raise
        return walk(namespaces, short)


def _bind_params(
    ctx: Context, node: Element, macro: Macro, symbols: Scope, local: Scope
) -> list[str]:
    params = list(macro.params)
    for name, value in list(node.attrs.items()):
        if name not in params:
            valid = ", ".join(p for p in macro.params if not p.startswith("*")) or "none"
            raise ctx.error(
                f"Invalid parameter \"{name}\" for macro '{macro.name}' (parameters: {valid})",
                node,
                name,
            )
        params.remove(name)
        ctx.node, ctx.attr = node, name
        if local.define(name, eval_text(ctx, value, symbols), unevaluated=False):
            ctx.warn(f"redefining global symbol: {name}", node)
        node.attrs[name] = ""
    return params


def _bind_blocks(
    ctx: Context, node: Element, macro: Macro, params: list[str], local: Scope
) -> None:
    block = node.first_element()
    for param in params[:]:
        if param[0] == "*":
            if block is None:
                raise ctx.error(f"Not enough blocks for macro '{macro.name}'", node)
            params.remove(param)
            local.define(param, block, unevaluated=True)
            block = next_element(block)
    if block is not None:
        raise ctx.error(f"Unused block \"{block.tag}\" in call of macro '{macro.name}'", block)


def _bind_defaults(
    ctx: Context, node: Element, macro: Macro, params: list[str], symbols: Scope, local: Scope
) -> None:
    for param in params[:]:
        if param[0] == "*":
            continue
        forward, default = macro.defaults.get(param, (None, None))
        if forward is None and default is None:
            continue
        ctx.node, ctx.attr = macro.body, "params"
        if forward is None:
            value = eval_text(ctx, default or "", symbols)
        elif forward in symbols:
            value = symbols.lookup(forward)
        elif default is not None:
            value = eval_text(ctx, default, symbols)
        else:
            raise ctx.error(
                f"Undefined property to forward: {forward} (macro '{macro.name}' takes it "
                "from the caller's scope with '^')",
                node,
            )
        local.define(param, value, unevaluated=False)
        params.remove(param)
    if params:
        raise ctx.error(
            f"Undefined parameters [{','.join(params)}] in call of macro '{macro.name}'", node
        )


def handle_macro_call(
    ctx: Context, node: Element, macros: Scope, symbols: Scope, eval_all: EvalAll
) -> None:
    """Expand the macro call ``node`` in place."""
    if node.tag == "xacro:call":
        spec = node.attrs.get("macro")
        if spec is None:
            raise ctx.error("xacro:call: missing attribute 'macro'", node)
        ctx.node, ctx.attr = node, "macro"
        name = str(eval_text(ctx, spec, symbols))
        if not name:
            raise ctx.error("xacro:call is missing the 'macro' attribute", node)
        del node.attrs["macro"]
        node.tag = "xacro:" + name
    name = node.tag[6:]
    try:
        m_scope, s_scope, macro = _resolve_macro(name, macros, symbols)
    except KeyError:
        hint = close_matches(name, [n for n in macros.names() if not n.startswith("*")])
        suggestion = f"; did you mean {', '.join(repr(h) for h in hint)}?" if hint else ""
        raise ctx.error(f"unknown macro name: {node.tag}{suggestion}", node) from None
    if len(ctx.stack) >= ctx.limits.max_macro_depth:
        raise ctx.error(
            f"macro calls nested deeper than {ctx.limits.max_macro_depth} levels; "
            "does a recursive macro lack a stopping xacro:if?",
            node,
        )
    counter = [0]
    body = macro.body.clone(counter)
    ctx.charge_nodes(counter[0])
    ctx.stack.append(Frame("macro", macro.name, macro.defined, node))
    local = Scope(s_scope, s_scope.root)
    local_macros = Scope(m_scope, m_scope.root)
    params = _bind_params(ctx, node, macro, symbols, local)
    eval_all(ctx, node, macros, symbols)
    _bind_blocks(ctx, node, macro, params, local)
    _bind_defaults(ctx, node, macro, params, symbols, local)
    eval_all(ctx, body, local_macros, local)
    remove_previous_comments(ctx, node)
    if node.parent is not None and isinstance(node.parent, Element):
        import_xml_namespaces(ctx, node.parent, body.attrs)
    ctx.charge_work(replace_node(node, body, content_only=True))
    ctx.stack.pop()


def import_xml_namespaces(ctx: Context, parent: Element, attributes: dict[str, str]) -> None:
    """Lift ``xmlns:*`` declarations to ``parent``; warn about conflicting redefinitions."""
    for name, value in attributes.items():
        if name.startswith("xmlns:"):
            old = parent.attrs.get(name)
            if old is not None and old != value:
                ctx.warn(
                    f"inconsistent namespace redefinitions for {name}: old: {old} new: {value}"
                )
            else:
                parent.attrs[name] = value


def read_document(ctx: Context, filename: str) -> Document:
    """Read and parse ``filename`` (relative to the root directory)."""
    data = read_user_bytes(os.path.join(ctx.root_dir, filename), what="xacro file")
    ctx.sources[filename] = data
    return parse_xml(data, filename)


def _include_files(ctx: Context, spec: str) -> list[str]:
    if re.search(r"[*[?]+", spec):
        names = sorted(glob.glob(spec))
        if not names:
            ctx.warn(f'Include tag\'s filename spec "{spec}" matched no files.')
    else:
        names = [spec]
    for name in names:
        ctx.record_include(name)
    return names


def process_include(
    ctx: Context, elt: Element, macros: Scope, symbols: Scope, eval_all: EvalAll
) -> None:
    """Replace ``<xacro:include>`` by the processed content of the included file(s)."""
    filename_spec, ns_spec, optional_text = check_attrs(ctx, elt, ["filename"], ["ns", "optional"])
    ns_macros, ns_symbols = macros, symbols
    if ns_spec:
        ctx.node, ctx.attr = elt, "ns"
        ns = str(eval_text(ctx, ns_spec, symbols))
        ns_macros = Scope(None, {}, namespace=True)
        ns_symbols = Scope(symbols, symbols.root, namespace=True)
        macros.define(ns, ns_macros, unevaluated=False)
        if symbols.define(ns, ns_symbols, unevaluated=False):
            ctx.warn(f"redefining global symbol: {ns}", elt)
    try:
        optional = to_boolean(optional_text, None)
    except BooleanError as exc:
        raise ctx.error(str(exc), elt, "optional") from None
    if elt.first_element() is not None:
        ctx.warn("Child elements of a <xacro:include> tag are ignored", elt)
    ctx.node, ctx.attr = elt, "filename"
    spec = abs_filename_spec(ctx, str(eval_text(ctx, filename_spec or "", symbols)))
    included: list[Element] = []
    for filename in _include_files(ctx, spec):
        try:
            document = read_document(ctx, filename)
        except UserFileError as exc:
            if optional and exc.errno is not None:  # missing or unreadable, as the reference
                continue
            raise ctx.error(f"cannot include '{filename}': {exc.reason}", elt, "filename") from None
        root = document.root
        if len(ctx.stack) >= ctx.limits.max_macro_depth:
            raise ctx.error(
                f"includes and macro calls nested deeper than {ctx.limits.max_macro_depth} "
                "levels; does a file include itself?",
                elt,
            )
        ctx.stack.append(Frame("include", filename, None, elt))
        ctx.filestack.append(filename)
        ctx.charge_nodes(document.size)
        eval_all(ctx, root, ns_macros, ns_symbols)
        included.append(root)
        if isinstance(elt.parent, Element):
            import_xml_namespaces(ctx, elt.parent, root.attrs)
        ctx.filestack.pop()
        ctx.stack.pop()
    remove_previous_comments(ctx, elt)
    ctx.charge_work(replace_node(elt, included, content_only=True))
