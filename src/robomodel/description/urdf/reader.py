"""Reading a URDF document into the model, with urdfdom's fatal/non-fatal split.

Order of work, as urdfdom's ``parseURDF``: XML, the ``<robot>`` element and its name, the
version, robot-level materials, links, "no links", joints, then the tree (parents, children in
joint-name order, exactly one root). Fatal problems raise :class:`InputError`; everything else
becomes a warning diagnostic. The XML parser never resolves entities, loads DTDs or touches the
network, and documents declaring entities are refused (billion laughs, external entities).
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol, TypeVar

from lxml import etree

from robomodel._files import UserFileError, read_user_bytes
from robomodel._gc import paused_gc
from robomodel.description.model import (
    Link,
    Material,
    RawElement,
    Robot,
    SourceText,
    TreeError,
)
from robomodel.description.urdf.context import ElementError, ParseContext, Version, local_tag
from robomodel.description.urdf.read_extensions import (
    read_gazebo,
    read_ros2_control,
    read_transmission,
)
from robomodel.description.urdf.read_joint import read_joint
from robomodel.description.urdf.read_link import raw, read_link, read_material
from robomodel.errors import Diagnostic, InputError, Severity, SourceLocation

__all__ = ["MAX_INPUT_BYTES", "ParseResult", "URDFWarning", "parse_urdf", "read_urdf"]

MAX_INPUT_BYTES = 32 * 1024 * 1024
SUPPORTED_VERSIONS: tuple[Version, ...] = ((1, 0), (1, 1), (1, 2))


class URDFWarning(UserWarning):
    """A non-fatal problem found while reading a URDF (see :func:`read_urdf`)."""


@dataclass(frozen=True, slots=True)
class ParseResult:
    """A parsed robot and every non-fatal diagnostic found on the way."""

    robot: Robot
    diagnostics: tuple[Diagnostic, ...]


Source = str | bytes | os.PathLike[str]


def _load(source: Source, path: str | None, max_bytes: int) -> tuple[bytes, str | None]:
    if isinstance(source, bytes):
        data = source
    elif isinstance(source, str) and source.lstrip().startswith("<"):
        data = source.encode("utf-8")
        if source.lstrip().startswith("<?xml"):
            # An encoding declaration would contradict the UTF-8 bytes we hand to libxml2.
            data = _strip_encoding(data)
    else:
        path = path or str(source)
        try:
            data = read_user_bytes(source, what="file", limit=max_bytes)
        except UserFileError as exc:
            raise InputError.at(
                exc.reason
                + ("; this is not a URDF file, or pass max_bytes=..." if exc.too_large else ""),
                path,
                code="too-large" if exc.too_large else "io",
            ) from None
    if len(data) > max_bytes:
        raise InputError.at(
            f"document is {len(data) / 1e6:.1f} MB, larger than the "
            f"{max_bytes / 1e6:.0f} MB limit for a robot description",
            path,
            1,
            1,
            code="too-large",
        )
    return data, path


def _strip_encoding(data: bytes) -> bytes:
    end = data.find(b"?>")
    head = data[:end]
    start = head.find(b"encoding")
    if start < 0:
        return data
    quote_pos = start + head[start:].find(b"=") + 1
    while head[quote_pos : quote_pos + 1] in (b" ", b"\t"):
        quote_pos += 1
    close = head.find(head[quote_pos : quote_pos + 1], quote_pos + 1)
    return data[:start] + data[close + 1 :]


def _parse_xml(data: bytes, path: str | None) -> etree._Element:
    if not data.strip():
        raise InputError.at(
            'the document is empty; a URDF file holds <robot name="..."> ... </robot>',
            path,
            1,
            1,
            code="xml",
        )
    _refuse_entities(data, path)
    parser = etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        dtd_validation=False,
        huge_tree=False,
        remove_blank_text=False,
    )
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError as exc:
        line, column = exc.position if exc.position else (1, 1)
        message = exc.msg.rsplit(", line ", 1)[0] if exc.msg else "malformed XML"
        raise InputError.at(f"malformed XML: {message}", path, line, column, code="xml") from None
    return root


def _refuse_entities(data: bytes, path: str | None) -> None:
    """Refuse DTD entity declarations before libxml2 sees them (bombs, file disclosure)."""
    doctype = data.find(b"<!DOCTYPE")
    entity = data.find(b"<!ENTITY")
    if doctype < 0 or entity < doctype:
        return
    end = data.find(b">", entity)
    declaration = data[entity : end + 1 if end >= 0 else entity + 60].decode("utf-8", "replace")
    line = data.count(b"\n", 0, entity) + 1
    column = entity - data.rfind(b"\n", 0, entity)
    raise InputError.at(
        f"entity declarations are not allowed ({declaration[:60]}); they enable "
        "entity-expansion bombs and reading local files",
        path,
        line,
        column,
        code="xml-entity",
    )


def _version(ctx: ParseContext, root: etree._Element) -> Version:
    """Parse ``robot@version`` with urdfdom's ``URDFVersion`` rules and messages."""
    text = root.get("version")
    if text is None:
        return (1, 0)
    pieces = text.split(".")
    if len(pieces) > 1 and pieces[-1] == "":
        pieces.pop()  # urdfdom's split_string drops a trailing empty field
    if len(pieces) != 2:
        ctx.fatal(
            f"The version attribute should be in the form 'x.y' (got '{text}')", root, "version"
        )
    numbers = []
    for piece in pieces:
        if piece == "":
            ctx.fatal("One of the fields of the version attribute is blank", root, "version")
        stripped = piece.lstrip(" \t\n")
        digits = stripped.lstrip("+-")
        count = len(digits) - len(digits.lstrip("0123456789"))
        if count == 0:
            ctx.fatal("Version attribute is not an integer", root, "version")
        if digits[count:]:
            ctx.fatal("Extra characters after the version number", root, "version")
        value = int(stripped[: len(stripped) - len(digits) + count])
        if value < 0:
            ctx.fatal("Version number must be positive", root, "version")
        numbers.append(value)
    version = (numbers[0], numbers[1])
    if version not in SUPPORTED_VERSIONS:
        ctx.fatal(
            f"Invalid 'version' specified ({text}); versions from 1.0 upto 1.2 are currently "
            "supported",
            root,
            "version",
        )
    return version


def read_urdf(
    source: Source, *, path: str | None = None, max_bytes: int = MAX_INPUT_BYTES
) -> ParseResult:
    """Parse URDF from a path, XML text or bytes.

    Args:
        source: A file path, or the document itself as ``str`` (starting with ``<``) or bytes.
        path: The name to report in diagnostics when ``source`` is text.
        max_bytes: Refuse larger inputs.

    Returns:
        The robot and its non-fatal diagnostics (urdfdom's non-fatal errors and warnings,
        plus robomodel's extra checks).

    Raises:
        InputError: where urdfdom is fatal, with ``file:line:column``.
    """
    data, path = _load(source, path, max_bytes)
    with paused_gc():
        return _read(data, path)


def _read(data: bytes, path: str | None) -> ParseResult:
    root = _parse_xml(data, path)
    ctx = ParseContext(path, SourceText(data, path))
    if local_tag(root) != "robot":
        ctx.fatal(
            f"Could not find the 'robot' element in the xml file (the root element is "
            f'<{local_tag(root)}>); a URDF file\'s root is <robot name="...">',
            root,
            "robot",
        )
    name = root.get("name")
    if name is None:
        ctx.fatal('No name given for the robot; add name="..." to <robot>', root, "robot-name")
    ctx.version = _version(ctx, root)
    robot = _read_robot(ctx, root, name)
    from robomodel.description.validate import validate

    diagnostics = ctx.diagnostics + validate(robot)
    return ParseResult(robot, tuple(diagnostics))


def parse_urdf(
    source: Source, *, path: str | None = None, max_bytes: int = MAX_INPUT_BYTES
) -> Robot:
    """Parse URDF and return the robot; non-fatal diagnostics become :class:`URDFWarning`."""
    result = read_urdf(source, path=path, max_bytes=max_bytes)
    for diagnostic in result.diagnostics:
        warnings.warn(diagnostic.format(), URDFWarning, stacklevel=2)
    return result.robot


def _read_robot(ctx: ParseContext, root: etree._Element, name: str) -> Robot:
    groups: dict[str, list[etree._Element]] = {
        "material": [],
        "link": [],
        "joint": [],
        "transmission": [],
        "gazebo": [],
        "ros2_control": [],
    }
    extra: list[RawElement] = []
    for child in root:
        tag = child.tag
        if not isinstance(tag, str):
            continue
        group = groups.get(tag if tag[0] != "{" else local_tag(child))
        if group is None:
            extra.append(raw(ctx, child))
        else:
            group.append(child)
    materials = _read_unique(ctx, groups["material"], _robot_material, "material")
    links = _read_unique(ctx, groups["link"], read_link, "link")
    _check_link_materials(ctx, links, materials)
    if not links:
        ctx.fatal(
            "No link elements found in urdf file; a robot needs at least one <link>",
            root,
            "no-links",
        )
    joints = _read_unique(ctx, groups["joint"], read_joint, "joint")
    transmissions = _read_optional(ctx, read_transmission, groups["transmission"], extra)
    gazebo = _read_optional(ctx, read_gazebo, groups["gazebo"], extra)
    ros2 = _read_optional(ctx, read_ros2_control, groups["ros2_control"], extra)
    attributes = tuple((k, v) for k, v in root.attrib.items() if k not in ("name", "version"))
    robot = Robot(
        name,
        tuple(links),
        tuple(joints),
        tuple(materials),
        tuple(transmissions),
        tuple(gazebo),
        tuple(ros2),
        tuple(extra),
        root.get("version"),
        attributes,
        ctx.path,
    )
    try:
        robot.tree()
    except TreeError as exc:
        element = None
        if exc.joint is not None:
            element = next((e for e in groups["joint"] if e.get("name") == exc.joint), None)
        ctx.fatal(str(exc), element if element is not None else root, "tree")
    return robot


_T = TypeVar("_T")


def _read_optional(
    ctx: ParseContext,
    reader: Callable[[ParseContext, etree._Element], _T],
    elements: list[etree._Element],
    extra: list[RawElement],
) -> list[_T]:
    """Read extension blocks; a broken one is warned about and kept verbatim in ``extra``."""
    out: list[_T] = []
    for element in elements:
        try:
            out.append(reader(ctx, element))
        except ElementError as exc:
            ctx.warn(
                f"{exc.message}; the element is kept verbatim",
                exc.element if exc.element is not None else element,
            )
            extra.append(raw(ctx, element))
    return out


class _Named(Protocol):
    @property
    def name(self) -> str: ...


_N = TypeVar("_N", bound=_Named)


def _read_unique(
    ctx: ParseContext,
    elements: list[etree._Element],
    reader: Callable[[ParseContext, etree._Element], _N | None],
    kind: str,
) -> list[_N]:
    """Read elements in file order; a repeated name is fatal, as in urdfdom's model.cpp."""
    items: list[_N] = []
    seen: set[str] = set()
    for element in elements:
        item = reader(ctx, element)
        if item is None:
            continue
        if item.name in seen:
            ctx.fatal(f"{kind} '{item.name}' is not unique.", element, f"duplicate-{kind}")
        seen.add(item.name)
        items.append(item)
    return items


def _robot_material(ctx: ParseContext, element: etree._Element) -> Material | None:
    try:
        return read_material(ctx, element, only_name_is_ok=False)
    except ElementError as exc:
        ctx.error(exc.message, exc.element if exc.element is not None else element, "material")
        return None


def _check_link_materials(ctx: ParseContext, links: list[Link], materials: list[Material]) -> None:
    """Warn about visual materials that name nothing (urdfdom's material resolution order)."""
    known = {m.name for m in materials}
    for link in links:
        for visual in link.visuals:
            material = visual.material
            if material is None or material.name in known:
                continue
            if not material.is_reference:
                known.add(material.name)  # inline definitions register globally
                continue
            location = material.span.location if material.span else SourceLocation(ctx.path)
            ctx.diagnostics.append(
                Diagnostic(
                    Severity.WARNING,
                    f"link '{link.name}' material '{material.name}' undefined; define "
                    f'<material name="{material.name}"> at robot level or inline with <color>',
                    location,
                    "material-undefined",
                )
            )
