"""The ``xacro`` module's Python API, backed by robomodel's xacro."""

from __future__ import annotations

import os
from typing import Any
from xml.dom import minidom

from robomodel._files import UserFileError, read_user_bytes
from robomodel.errors import RobomodelError
from robomodel.launch.ros2.shim.context import SubstitutionFailure, current_session

__all__ = ["parse", "process_doc", "process_file"]


def _packages() -> Any:
    session = current_session()
    return None if session is None else session.packages


def process_file(input_file_name: Any, **kwargs: Any) -> Any:
    """``xacro.process_file(path, mappings=...)``: the expanded document (``.toxml()``)."""
    from robomodel import xacro

    mappings = kwargs.get("mappings")
    try:
        return xacro.process_file(os.fspath(input_file_name), mappings, package_index=_packages())
    except RobomodelError as exc:
        raise SubstitutionFailure(f"xacro: {exc}") from None


def parse(inp: Any, filename: str | None = None) -> minidom.Document:
    """``xacro.parse``: a minidom document from XML text, a file name or a file object."""
    if hasattr(inp, "read"):
        return minidom.parseString(inp.read())
    text = str(inp)
    if text.lstrip().startswith("<"):
        return minidom.parseString(text)
    try:
        return minidom.parseString(read_user_bytes(text, what="xacro file"))
    except UserFileError as exc:
        raise SubstitutionFailure(f"xacro: {exc}") from None


def process_doc(doc: minidom.Document, mappings: Any = None, **kwargs: Any) -> None:
    """``xacro.process_doc``: expand ``doc`` in place."""
    from robomodel import xacro

    try:
        text = xacro.process(doc.toxml(), mappings, package_index=_packages())
    except RobomodelError as exc:
        raise SubstitutionFailure(f"xacro: {exc}") from None
    expanded = minidom.parseString(text)
    for child in list(doc.childNodes):
        doc.removeChild(child)
    for child in list(expanded.childNodes):
        doc.appendChild(doc.importNode(child, True))  # type: ignore[type-var]
