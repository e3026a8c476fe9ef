"""A minimal DOM with minidom's node semantics, built for speed.

The reference xacro works on ``xml.dom.minidom`` trees; its output depends on details such as
adjacent text nodes staying separate after a macro expansion. These classes keep exactly those
semantics (a doubly linked list of children per parent) with ``__slots__`` and a cheap deep copy.
Every node remembers where it came from (file, line, column) for error messages.
"""

from __future__ import annotations

from collections.abc import Iterator

__all__ = [
    "CData",
    "Comment",
    "Document",
    "Element",
    "Node",
    "ProcessingInstruction",
    "Text",
]


class Node:
    """Base of every node: parent and sibling links plus the source position."""

    __slots__ = ("column", "file", "line", "next", "parent", "prev")

    def __init__(self, file: str | None = None, line: int = 0, column: int = 0) -> None:
        self.parent: Element | Document | None = None
        self.prev: Node | None = None
        self.next: Node | None = None
        self.file = file
        self.line = line
        self.column = column

    def clone(self) -> Node:
        """Return a deep copy without parent links (minidom's ``cloneNode(deep=True)``)."""
        raise NotImplementedError


class _CharacterData(Node):
    __slots__ = ("data",)

    def __init__(self, data: str, file: str | None = None, line: int = 0, column: int = 0) -> None:
        Node.__init__(self, file, line, column)
        self.data = data

    def clone(self) -> Node:
        copy = type(self)(self.data, self.file, self.line, self.column)
        return copy


class Text(_CharacterData):
    """A text node; adjacent text nodes are not merged (as in minidom after edits)."""

    __slots__ = ()


class CData(_CharacterData):
    """A CDATA section: never evaluated, printed verbatim."""

    __slots__ = ()


class Comment(_CharacterData):
    """A comment node."""

    __slots__ = ()


class ProcessingInstruction(Node):
    """A processing instruction ``<?target data?>``."""

    __slots__ = ("data", "target")

    def __init__(self, target: str, data: str, file: str | None = None, line: int = 0) -> None:
        Node.__init__(self, file, line, 0)
        self.target = target
        self.data = data

    def clone(self) -> Node:
        return ProcessingInstruction(self.target, self.data, self.file, self.line)


class _Container(Node):
    __slots__ = ("first", "last")

    def __init__(self, file: str | None = None, line: int = 0, column: int = 0) -> None:
        Node.__init__(self, file, line, column)
        self.first: Node | None = None
        self.last: Node | None = None

    def children(self) -> Iterator[Node]:
        """Iterate over the children (safe against removal of the current child)."""
        node = self.first
        while node is not None:
            following = node.next
            yield node
            node = following

    def append(self, node: Node) -> None:
        """Append ``node`` as the last child, detaching it from its old parent first."""
        if node.parent is not None:
            node.parent.remove(node)
        node.parent = self  # type: ignore[assignment]
        node.prev = self.last
        node.next = None
        if self.last is None:
            self.first = node
        else:
            self.last.next = node
        self.last = node

    def insert_before(self, node: Node, ref: Node | None) -> None:
        """Insert ``node`` before ``ref`` (append when ``ref`` is None)."""
        if ref is None:
            self.append(node)
            return
        if node.parent is not None:
            node.parent.remove(node)
        node.parent = self  # type: ignore[assignment]
        node.next = ref
        node.prev = ref.prev
        if ref.prev is None:
            self.first = node
        else:
            ref.prev.next = node
        ref.prev = node

    def remove(self, node: Node) -> None:
        """Detach the child ``node``."""
        if node.prev is None:
            self.first = node.next
        else:
            node.prev.next = node.next
        if node.next is None:
            self.last = node.prev
        else:
            node.next.prev = node.prev
        node.parent = node.prev = node.next = None

    def first_element(self) -> Element | None:
        """Return the first child element, if any."""
        node = self.first
        while node is not None and not isinstance(node, Element):
            node = node.next
        return node


class Element(_Container):
    """An element with its qualified tag name and its attributes in document order."""

    __slots__ = ("attrs", "offset", "tag")

    def __init__(
        self,
        tag: str,
        attrs: dict[str, str] | None = None,
        file: str | None = None,
        line: int = 0,
        column: int = 0,
        offset: int = -1,
    ) -> None:
        _Container.__init__(self, file, line, column)
        self.tag = tag
        self.attrs: dict[str, str] = dict(attrs) if attrs else {}
        self.offset = offset

    def clone(self) -> Element:
        copy = Element(self.tag, None, self.file, self.line, self.column, self.offset)
        copy.attrs = self.attrs.copy()
        node = self.first
        prev: Node | None = None
        while node is not None:
            child = node.clone()
            child.parent = copy
            child.prev = prev
            if prev is None:
                copy.first = child
            else:
                prev.next = child
            prev = child
            node = node.next
        copy.last = prev
        return copy


class Document(_Container):
    """The document: leading comments and PIs, the root element, trailing nodes."""

    __slots__ = ()

    @property
    def root(self) -> Element:
        """The document element."""
        root = self.first_element()
        if root is None:  # the parser guarantees a root element
            raise ValueError("document has no root element")
        return root

    def clone(self) -> Document:
        copy = Document(self.file)
        for child in self.children():
            copy.append(child.clone())
        return copy


def next_element(node: Node) -> Element | None:
    """Return the next sibling element of ``node``, if any."""
    sibling = node.next
    while sibling is not None and not isinstance(sibling, Element):
        sibling = sibling.next
    return sibling
