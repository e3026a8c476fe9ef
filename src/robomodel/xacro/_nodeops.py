"""Tree edits with the reference's exact side effects (xmlutils.py and L269/L881)."""

from __future__ import annotations

from collections.abc import Sequence

from robomodel.xacro._context import Context
from robomodel.xacro._dom import Comment, Element, Node, Text

__all__ = ["check_attrs", "remove_previous_comments", "replace_node"]


def replace_node(node: Node, by: list[Element] | Element | None, content_only: bool = False) -> int:
    """Insert ``by`` (or its children when ``content_only``) before ``node``; drop ``node``.

    Returns how many nodes were moved (the work an expansion is charged for)."""
    parent = node.parent
    if parent is None:
        return 0
    moved = 0
    if by is not None:
        for doc in by if isinstance(by, list) else (by,):
            if content_only:
                child = doc.first
                while child is not None:
                    following = child.next
                    parent.insert_before(child, node)
                    child = following
                    moved += 1
            else:
                parent.insert_before(doc, node)
                moved += 1
    parent.remove(node)
    return moved


def remove_previous_comments(ctx: Context, node: Node) -> None:
    """Remove the comments right before a xacro tag; a single blank line is tolerated.

    Like the reference, a shared blank text node is then moved after the tag so that the
    comments further up are not removed by a later tag.
    """
    parent = node.parent
    following = node.next
    previous = node.prev
    while previous is not None:
        if type(previous) is Text and previous.data.isspace() and previous.data.count("\n") <= 1:
            previous = previous.prev
        if previous is not None and type(previous) is Comment:
            comment = previous
            previous = previous.prev
            if parent is not None:
                parent.remove(comment)
        else:
            if following is not None and following is not ctx.empty_text and parent is not None:
                parent.insert_before(ctx.empty_text, following)
            return


def check_attrs(
    ctx: Context, tag: Element, required: Sequence[str], optional: Sequence[str]
) -> list[str | None]:
    """Fetch required and optional attributes; warn about unknown ones."""
    result: list[str | None] = []
    for name in required:
        value = tag.attrs.get(name)
        if value is None:
            raise ctx.error(f"{tag.tag}: missing attribute '{name}'", tag)
        result.append(value)
    result.extend(tag.attrs.get(name) for name in optional)
    allowed = (*required, *optional)
    extra = [a for a in tag.attrs if a not in allowed and not a.startswith("xmlns:")]
    if extra:
        valid = ", ".join(allowed)
        ctx.warn(f"{tag.tag}: unknown attribute(s): {', '.join(extra)} (valid: {valid})", tag)
    return result
