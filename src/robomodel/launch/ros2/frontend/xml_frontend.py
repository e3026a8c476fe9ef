"""XML launch files (launch_xml): ``<launch>`` elements to actions."""

from __future__ import annotations

from pathlib import Path

from lxml import etree

from robomodel._files import UserFileError, read_user_bytes
from robomodel.errors import SourceLocation
from robomodel.launch.model import LaunchError
from robomodel.launch.ros2.frontend.build import build_description
from robomodel.launch.ros2.frontend.entity import Entity
from robomodel.launch.ros2.shim.action import LaunchDescription
from robomodel.launch.ros2.shim.context import current_session
from robomodel.launch.ros2.shim.sources import FileLoader

__all__ = ["XML_LOADER", "load_xml_description"]


def _entity(element: etree._Element, path: str) -> Entity:
    children = [_entity(child, path) for child in element if isinstance(child.tag, str)]
    return Entity(
        type_name=str(element.tag),
        attrs=dict(element.attrib),
        children=children,
        location=SourceLocation(path, element.sourceline),
    )


def load_xml_description(path: Path) -> LaunchDescription:
    """Parse an XML launch file into a LaunchDescription."""
    session = current_session()
    stack = tuple(session.include_stack) if session is not None else ()
    try:
        data = read_user_bytes(path, what="launch file")
        parser = etree.XMLParser(
            remove_comments=True, resolve_entities=False, no_network=True, load_dtd=False
        )
        root = etree.fromstring(data, parser)
    except UserFileError as exc:
        raise LaunchError(str(exc), include_stack=stack) from None
    except etree.XMLSyntaxError as exc:
        line, column = exc.position if exc.position else (None, None)
        raise LaunchError(
            f"invalid XML: {exc.msg}",
            location=SourceLocation(str(path), line, column),
            include_stack=stack,
        ) from None
    entity = _entity(root, str(path))
    if entity.type_name != "launch":
        raise LaunchError(
            f"the root element of a launch file must be <launch>, not <{entity.type_name}>",
            location=entity.location,
            include_stack=stack,
        )
    return build_description(entity.children, entity.location)


XML_LOADER = FileLoader("xml", (".xml",), load_xml_description)
