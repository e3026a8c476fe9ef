"""A minimal DOM with minidom's node semantics, built for speed.

The reference xacro works on ``xml.dom.minidom`` trees; its output depends on details such as
adjacent text nodes staying separate after a macro expansion. These classes keep exactly those
semantics (a doubly linked list of children per parent) with ``__slots__`` and a cheap deep copy.
Every node remembers where it came from, as one shared tuple ``loc = (file, line, column,
byte_offset)``, for error messages.
"""

from __future__ import annotations

from collections.abc import Iterator

__all__ = [
    "CData",
    "Comment",
    "Document",
    "Element",
    "Location",
    "Node",
    "ProcessingInstruction",
    "Text",
    "next_element",
]

Location = tuple[str | None, int, int, int]
NOWHERE: Location = (None, 0, 0, -1)


class Node:
    """Base of every node: parent and sibling links plus the source position."""

    __slots__ = ("loc", "next", "parent", "prev")

    parent: Element | Document | None
    prev: Node | None
    next: Node | None
    loc: Location

    @property
    def file(self) -> str | None:
        """The file this node was read from."""
        return self.loc[0]

    @property
    def line(self) -> int:
        """1-based line of the node's start (0 when unknown)."""
        return self.loc[1]

    @property
    def column(self) -> int:
        """1-based column of the node's start (0 when unknown)."""
        return self.loc[2]

    @property
    def offset(self) -> int:
        """Byte offset of the node's start in its file (-1 when unknown)."""
        return self.loc[3]

    def clone(self) -> Node:
        """Return a deep copy without parent links (minidom's ``cloneNode(deep=True)``)."""
        raise NotImplementedError


class _CharacterData(Node):
    __slots__ = ("data",)

    def __init__(self, data: str, loc: Location = NOWHERE) -> None:
        self.parent = self.prev = self.next = None
        self.loc = loc
        self.data = data

    def clone(self) -> Node:
        copy = _new(type(self))
        copy.parent = copy.prev = copy.next = None
        copy.loc = self.loc
        copy.data = self.data
        return copy


_new = object.__new__


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

    def __init__(self, target: str, data: str, loc: Location = NOWHERE) -> None:
        self.parent = self.prev = self.next = None
        self.loc = loc
        self.target = target
        self.data = data

    def clone(self) -> Node:
        return ProcessingInstruction(self.target, self.data, self.loc)


class _Container(Node):
    __slots__ = ("first", "last")

    first: Node | None
    last: Node | None

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
        node.prev = last = self.last
        node.next = None
        if last is None:
            self.first = node
        else:
            last.next = node
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
        node.prev = prev = ref.prev
        if prev is None:
            self.first = node
        else:
            prev.next = node
        ref.prev = node

    def remove(self, node: Node) -> None:
        """Detach the child ``node``."""
        prev, following = node.prev, node.next
        if prev is None:
            self.first = following
        else:
            prev.next = following
        if following is None:
            self.last = prev
        else:
            following.prev = prev
        node.parent = node.prev = node.next = None

    def first_element(self) -> Element | None:
        """Return the first child element, if any."""
        node = self.first
        while node is not None and type(node) is not Element:
            node = node.next
        return node


class Element(_Container):
    """An element with its qualified tag name and its attributes in document order."""

    __slots__ = ("attrs", "tag")

    def __init__(
        self, tag: str, attrs: dict[str, str] | None = None, loc: Location = NOWHERE
    ) -> None:
        self.parent = self.prev = self.next = self.first = self.last = None
        self.loc = loc
        self.tag = tag
        self.attrs: dict[str, str] = attrs if attrs is not None else {}

    def clone(self, counter: list[int] | None = None) -> Element:
        """Deep copy; when given, ``counter[0]`` is increased by the number of nodes copied."""
        copy: Element = _new(Element)
        copy.parent = copy.prev = copy.next = None
        copy.loc = self.loc
        copy.tag = self.tag
        copy.attrs = self.attrs.copy()
        prev: Node | None = None
        node = self.first
        while node is not None:
            kind = type(node)
            if kind is Element:
                child: Node = node.clone(counter)  # type: ignore[call-arg]
            elif kind is ProcessingInstruction:
                child = node.clone()
            else:
                child = _new(kind)
                child.loc = node.loc
                child.data = node.data  # type: ignore[attr-defined]
            child.parent = copy
            child.prev = prev
            if prev is None:
                copy.first = child
            else:
                prev.next = child
            prev = child
            node = node.next
        if prev is None:
            copy.first = None
        else:
            prev.next = None
        copy.last = prev
        if counter is not None:
            counter[0] += 1
        return copy


class Document(_Container):
    """The document: leading comments and PIs, the root element, trailing nodes."""

    __slots__ = ("size",)

    def __init__(self, file: str | None = None) -> None:
        self.parent = self.prev = self.next = self.first = self.last = None
        self.loc = (file, 0, 0, -1)
        self.size = 0  # elements, as counted by the parser

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
    while sibling is not None and type(sibling) is not Element:
        sibling = sibling.next
    return sibling
