"""YAML launch files (launch_yaml): ``launch: [ {tag: {...}}, ... ]`` to actions."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from robomodel._files import UserFileError, read_user_text
from robomodel._yaml_bounded import YamlNestingError, load_yaml_file
from robomodel.errors import SourceLocation
from robomodel.launch.model import LaunchError
from robomodel.launch.ros2.frontend.build import build_description
from robomodel.launch.ros2.frontend.entity import Entity
from robomodel.launch.ros2.shim.action import LaunchDescription
from robomodel.launch.ros2.shim.context import current_session
from robomodel.launch.ros2.shim.sources import FileLoader

__all__ = ["YAML_LOADER", "load_yaml_description"]

_LINE = "__line__"
_NESTED_LISTS = ("param", "remap", "arg", "env", "choice", "keep")


class _LineLoader(yaml.SafeLoader):
    """A SafeLoader that records each mapping's line as ``__line__``."""


def _mapping(loader: _LineLoader, node: yaml.MappingNode) -> dict[str, Any]:
    mapping: dict[str, Any] = {
        str(k): v for k, v in loader.construct_mapping(node, deep=True).items()
    }
    mapping[_LINE] = node.start_mark.line + 1
    return mapping


_LineLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _mapping)


def _entities(items: Any, path: str, where: int, type_name: str | None = None) -> list[Entity]:
    if not isinstance(items, list):
        raise LaunchError(
            "expected a list of launch entities", location=SourceLocation(path, where)
        )
    return [_entity(item, path, type_name) for item in items]


def _entity(item: Any, path: str, type_name: str | None) -> Entity:
    line = item.get(_LINE) if isinstance(item, dict) else None
    location = SourceLocation(path, line)
    if type_name is None:
        keys = [k for k in item if k != _LINE] if isinstance(item, dict) else []
        if len(keys) != 1:
            raise LaunchError(
                "each launch entity must be a mapping with one key (its tag)", location=location
            )
        type_name = keys[0]
        body = item[type_name]
        if isinstance(body, dict):
            line = body.get(_LINE, line)
        item = body if body is not None else {}
    if not isinstance(item, dict):
        raise LaunchError(f"'{type_name}' must be a mapping", location=location)
    attrs = {
        k: v for k, v in item.items() if k != _LINE and k not in _NESTED_LISTS and k != "children"
    }
    lists = {
        k: _entities(v, path, line or 0, type_name=k) for k, v in item.items() if k in _NESTED_LISTS
    }
    children = _entities(item["children"], path, line or 0) if "children" in item else []
    if (
        type_name == "param"
        and isinstance(item.get("value"), list)
        and item["value"]
        and isinstance(item["value"][0], dict)
    ):
        lists["param"] = _entities(item["value"], path, line or 0, type_name="param")
        attrs.pop("value")
    return Entity(
        type_name=str(type_name),
        attrs=attrs,
        children=children,
        location=SourceLocation(path, line),
        lists=lists,
    )


def load_yaml_description(path: Path) -> LaunchDescription:
    """Parse a YAML launch file into a LaunchDescription."""
    session = current_session()
    stack = tuple(session.include_stack) if session is not None else ()
    try:
        text = read_user_text(path, what="launch file")
        data = load_yaml_file(text, where=str(path), loader=_LineLoader)
    except UserFileError as exc:
        raise LaunchError(str(exc), include_stack=stack) from None
    except YamlNestingError as exc:
        location = SourceLocation(str(path), exc.line or None, exc.column or None)
        raise LaunchError(exc.problem, location=location, include_stack=stack) from None
    except RecursionError:
        raise LaunchError(
            "YAML nested too deeply", location=SourceLocation(str(path)), include_stack=stack
        ) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        location = SourceLocation(str(path), mark.line + 1 if mark else None)
        raise LaunchError(f"invalid YAML: {exc}", location=location, include_stack=stack) from None
    if not isinstance(data, dict) or "launch" not in data:
        raise LaunchError(
            "a YAML launch file must have a top-level 'launch' list",
            location=SourceLocation(str(path)),
            include_stack=stack,
        )
    items = data["launch"] or []
    return build_description(_entities(items, str(path), 1), SourceLocation(str(path), 1))


YAML_LOADER = FileLoader("yaml", (".yaml", ".yml"), load_yaml_description)
