"""Parse XML text into the xacro DOM with expat, as minidom does, keeping source positions.

Expat with namespace processing is what ``xml.dom.minidom.parse`` uses, so the same documents
are accepted and rejected (an undeclared ``xacro:`` prefix is an "unbound prefix" error) and
attribute values get the same newline normalisation. Entity declarations are refused, which rules
out entity-expansion bombs; external entities are never fetched.
"""

from __future__ import annotations

import functools
from xml.parsers import expat

from robomodel.errors import Diagnostic, InputError, Severity, SourceLocation
from robomodel.xacro._dom import CData, Comment, Document, Element, ProcessingInstruction, Text

_new = object.__new__

__all__ = ["XML_HINT", "parse_xml"]

XML_HINT = (
    "check that the XML is well-formed and that the root element declares "
    'xmlns:xacro="http://www.ros.org/wiki/xacro"'
)


@functools.lru_cache(maxsize=4096)
def _qname(name: str) -> str:
    """Turn expat's ``uri local prefix`` triple back into the qualified name minidom uses."""
    if " " not in name:
        return name
    parts = name.split(" ")
    if len(parts) == 3:
        return f"{parts[2]}:{parts[1]}"
    return parts[1]


class _Builder:
    """Expat callbacks that build the DOM (the parts of minidom's ExpatBuilderNS we need)."""

    def __init__(self, parser: expat.XMLParserType, file: str | None) -> None:
        self.parser = parser
        self.file = file
        self.document = Document(file)
        self.current: Document | Element = self.document
        self.pending_ns: list[tuple[str, str]] = []
        self.in_cdata = False
        self.cdata_continue = False

    def start_ns(self, prefix: str | None, uri: str | None) -> None:
        self.pending_ns.append((prefix or "", uri or ""))

    def start_element(self, name: str, attrs: dict[str, str]) -> None:
        # The hot path of parsing: no helper calls for the common un-namespaced names.
        # Expat builds ``attrs`` in document order; namespaced names come as "uri local prefix".
        if attrs and " " in "".join(attrs):
            attrs = {_qname(key): value for key, value in attrs.items()}
        if self.pending_ns:
            declared = {("xmlns:" + p if p else "xmlns"): uri for p, uri in self.pending_ns}
            declared.update(attrs)
            attrs = declared
            self.pending_ns.clear()
        parser = self.parser
        element: Element = _new(Element)
        element.loc = (
            self.file,
            parser.CurrentLineNumber,
            parser.CurrentColumnNumber + 1,
            parser.CurrentByteIndex,
        )
        element.tag = _qname(name) if " " in name else name
        element.attrs = attrs
        element.first = element.last = element.next = None
        parent = self.current
        element.parent = parent
        last = parent.last
        element.prev = last
        if last is None:
            parent.first = element
        else:
            last.next = element
        parent.last = element
        self.current = element
        self.document.size += 1

    def end_element(self, name: str) -> None:
        parent = self.current.parent
        self.current = parent if parent is not None else self.document

    def characters(self, data: str) -> None:
        parent = self.current
        last = parent.last
        if self.in_cdata:
            if self.cdata_continue and isinstance(last, CData):
                last.data += data
                return
            node: Text | CData = CData(data, self._here())
            self.cdata_continue = True
        elif type(last) is Text:
            last.data += data
            return
        else:
            parser = self.parser
            node = _new(Text)
            node.data = data
            # buffer_text reports text when it ends: keep that offset to locate it later.
            node.loc = (
                self.file,
                parser.CurrentLineNumber,
                parser.CurrentColumnNumber + 1,
                parser.CurrentByteIndex,
            )
        node.parent = parent
        node.prev = last
        node.next = None
        if last is None:
            parent.first = node
        else:
            last.next = node
        parent.last = node

    def _here(self) -> tuple[str | None, int, int, int]:
        p = self.parser
        return (self.file, p.CurrentLineNumber, p.CurrentColumnNumber + 1, -1)

    def start_cdata(self) -> None:
        self.in_cdata = True
        self.cdata_continue = False

    def end_cdata(self) -> None:
        self.in_cdata = False
        self.cdata_continue = False

    def comment(self, data: str) -> None:
        self.current.append(Comment(data, self._here()))

    def pi(self, target: str, data: str) -> None:
        self.current.append(ProcessingInstruction(target, data, self._here()))

    def doctype(self, *args: object) -> None:
        raise _Refused("DOCTYPE declarations are not supported in xacro files")


class _Refused(Exception):
    """A construct the safe parser does not accept."""


def _error(message: str, file: str | None, line: int | None, column: int | None) -> InputError:
    location = SourceLocation(file, line, column)
    note = Diagnostic(Severity.NOTE, XML_HINT, location)
    return InputError(Diagnostic(Severity.ERROR, message, location), notes=(note,))


def parse_xml(data: bytes | str, file: str | None = None) -> Document:
    """Parse an XML document.

    Args:
        data: The document text (bytes are decoded by expat from the XML declaration).
        file: The path reported in positions and errors.

    Returns:
        The document; its root element is ``document.root``.

    Raises:
        InputError: the text is not well-formed XML, uses an undeclared prefix, or declares
            a DOCTYPE (refused so that entity expansion cannot be abused).
    """
    parser = expat.ParserCreate(namespace_separator=" ")
    parser.namespace_prefixes = True
    parser.ordered_attributes = False
    parser.specified_attributes = True
    parser.buffer_text = True
    builder = _Builder(parser, file)
    parser.StartNamespaceDeclHandler = builder.start_ns
    parser.StartElementHandler = builder.start_element
    parser.EndElementHandler = builder.end_element
    parser.CharacterDataHandler = builder.characters
    parser.StartCdataSectionHandler = builder.start_cdata
    parser.EndCdataSectionHandler = builder.end_cdata
    parser.CommentHandler = builder.comment
    parser.ProcessingInstructionHandler = builder.pi
    parser.StartDoctypeDeclHandler = builder.doctype
    parser.EntityDeclHandler = builder.doctype
    try:
        parser.Parse(data, True)
    except expat.ExpatError as exc:
        message = expat.errors.messages[exc.code] if exc.code else str(exc)
        raise _error(f"XML parsing error: {message}", file, exc.lineno, exc.offset + 1) from None
    except _Refused as exc:
        raise _error(
            str(exc), file, parser.CurrentLineNumber, parser.CurrentColumnNumber + 1
        ) from None
    return builder.document
