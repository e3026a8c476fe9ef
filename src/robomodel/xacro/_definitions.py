"""``<xacro:property>`` and ``<xacro:macro>`` definitions (reference L577-L690)."""

from __future__ import annotations

import re
from dataclasses import dataclass

from robomodel.errors import SourceLocation
from robomodel.xacro._context import Context
from robomodel.xacro._dom import Element
from robomodel.xacro._evaluation import eval_text
from robomodel.xacro._nodeops import (
    check_attrs,
    remove_previous_comments,
    replace_node,
)
from robomodel.xacro._symbols import BooleanError, Scope, is_valid_name, to_boolean

__all__ = ["Macro", "grab_macro", "grab_property", "parse_macro_arg", "parse_params"]

_DEFAULT = r"""\$\{.*?\}|\$\(.*?\)|(?:'.*?'|\".*?\"|[^\s'\"]+)+|"""
_MACRO_ARG = re.compile(r"^\s*([^\s:=]+?)\s*:?=\s*(\^\|?)?(" + _DEFAULT + r")(?:\s+|$)(.*)")


@dataclass(frozen=True, slots=True)
class Macro:
    """A macro definition.

    Attributes:
        name: The macro name.
        body: The ``<xacro:macro>`` element (cloned at every call).
        params: Parameter names in order, ``*blk``/``**blk`` for block parameters.
        defaults: ``param -> (forwarded name or None, default text or None)``.
        defined: Where the macro is defined.
    """

    name: str
    body: Element
    params: tuple[str, ...]
    defaults: dict[str, tuple[str | None, str | None]]
    defined: SourceLocation


def parse_macro_arg(s: str) -> tuple[str, tuple[str | None, str | None] | None, str]:
    """Parse the first parameter of ``s``: ``name``, ``name:=default``, ``name:=^|default``."""
    m = _MACRO_ARG.match(s)
    if m:
        param, forward, default, rest = m.groups()
        return param, (param if forward else None, default or None), rest
    parts = s.lstrip().split(None, 1)
    if not parts:
        return "", None, ""
    return parts[0], None, parts[1] if len(parts) > 1 else ""


def parse_params(params: str) -> tuple[list[str], dict[str, tuple[str | None, str | None]]]:
    """Parse a whole ``params`` attribute."""
    names: list[str] = []
    defaults: dict[str, tuple[str | None, str | None]] = {}
    while params:
        param, value, params = parse_macro_arg(params)
        if not param:
            break
        names.append(param)
        if value is not None:
            defaults[param] = value
    return names, defaults


def grab_macro(ctx: Context, elt: Element, macros: Scope) -> None:
    """Define a macro and remove its element."""
    remove_previous_comments(ctx, elt)
    name, params = check_attrs(ctx, elt, ["name"], ["params"])
    assert name is not None  # required attribute
    if name == "call":
        raise ctx.error("invalid use of macro name 'call' (reserved for <xacro:call>)", elt, "name")
    if "." in name:
        raise ctx.error(
            f"macro names must not contain '.' (reserved for namespaces): {name}", elt, "name"
        )
    if name.startswith("xacro:"):
        ctx.warn(f"macro names must not contain prefix 'xacro:': {name}", elt)
        name = name[6:]
    names, defaults = parse_params(params or "")
    macro = Macro(name, elt, tuple(names), defaults, ctx.location(elt))
    macros.define(name, macro, unevaluated=False)
    replace_node(elt, None)


def _boolean(
    ctx: Context, elt: Element, attr: str, text: str | None, default: str, table: Scope
) -> bool:
    ctx.node, ctx.attr = elt, attr
    try:
        return to_boolean(eval_text(ctx, text or default, table), text)
    except BooleanError as exc:
        raise ctx.error(str(exc), elt, attr) from None


def _target(ctx: Context, elt: Element, table: Scope, name: str, scope: str | None) -> Scope | None:
    if scope == "global":
        return table.top()
    if scope == "parent":
        if table.parent is None:
            # The reference crashes here (AttributeError); it meant to warn and ignore.
            ctx.warn(f"{name}: no parent scope at global scope; property ignored", elt)
            return None
        target = table.parent
        if not table.namespace:
            while target.namespace and target.parent is not None:
                target = target.parent
        return target
    return table


def grab_property(ctx: Context, elt: Element, table: Scope) -> None:
    """Define (or remove) a property and remove its element (reference ``grab_property``)."""
    remove_previous_comments(ctx, elt)
    attrs = ["value", "default", "remove", "scope", "lazy_eval"]
    name_text, value, default, remove_text, scope, lazy_text = check_attrs(
        ctx, elt, ["name"], attrs
    )
    ctx.node, ctx.attr = elt, "name"
    name = eval_text(ctx, name_text or "", table)
    if not is_valid_name(name):
        raise ctx.error(f"property names must be valid Python identifiers: {name}", elt, "name")
    assert isinstance(name, str)
    if name.startswith("__"):
        raise ctx.error(
            f"property names must not start with double underscore: {name}", elt, "name"
        )
    remove = _boolean(ctx, elt, "remove", remove_text, "false", table)
    if sum([value is not None, default is not None, remove]) > 1:
        raise ctx.error(
            f"Property attributes default, value, and remove are mutually exclusive: {name}", elt
        )
    if remove and name in table:
        if table.delete(name):
            ctx.warn(f"Cannot remove global symbol: {name}", elt)
        replace_node(elt, None)
        return
    if default is not None:
        if scope is not None:
            ctx.warn(f"{name}: default property value can only be defined on local scope", elt)
        if name in table:
            replace_node(elt, None)
            return
        value = default
    stored: object = value
    if value is None:
        name = "**" + name
        stored = elt
    replace_node(elt, None)
    lazy = _boolean(ctx, elt, "lazy_eval", lazy_text, "true", table)
    target = _target(ctx, elt, table, name, scope)
    if target is None:
        return
    if scope in ("global", "parent"):
        lazy = False
    if not lazy and isinstance(stored, str):
        ctx.node, ctx.attr = elt, "value" if value is not None and default is None else "default"
        stored = eval_text(ctx, stored, table)
    if target.define(name, stored, unevaluated=lazy):
        ctx.warn(f"redefining global symbol: {name}", elt)
