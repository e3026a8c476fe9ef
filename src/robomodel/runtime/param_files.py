"""A node's parameters from ROS 2 parameter files, as rcl resolves them.

In a file, the top-level keys are node names matched against the node's fully qualified name
(rcl's ``rcl_yaml_param_parser``): ``/**`` matches every node, ``*`` one name token and ``**``
any number of them, a name without a leading ``/`` is relative to the root; under the node key,
``ros__parameters`` holds the parameters, nested mappings as dotted names.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from robomodel._files import UserFileError, read_user_text
from robomodel.errors import RobomodelError

__all__ = ["flatten", "parameters_from_file"]


def flatten(values: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """Nested dicts as dotted names (``{"a": {"b": 1}}`` -> ``{"a.b": 1}``)."""
    out: dict[str, Any] = {}
    for key, value in values.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            out.update(flatten(value, name + "."))
        else:
            out[name] = value
    return out


def _pattern(key: str) -> re.Pattern[str]:
    regex = ""
    for token in key.lstrip("/").split("/"):
        if token == "**":
            regex += "(?:/[^/]+)*"
        else:
            regex += "/" + re.escape(token).replace(r"\*", "[^/]+")
    return re.compile("^" + regex + "$")


def _matches(key: str, fqn: str) -> bool:
    return bool(_pattern(key).match(fqn))


def parameters_from_file(path: Path, fqn: str) -> dict[str, Any]:
    """The parameters ``path`` gives node ``fqn`` (``/ns/name``), dotted names.

    Raises:
        RobomodelError: an unreadable file or YAML error, with its location.
    """
    import yaml

    from robomodel._yaml_bounded import YamlNestingError, load_yaml_file

    try:
        data = load_yaml_file(read_user_text(path, what="parameter file"), where=str(path))
    except (UserFileError, YamlNestingError) as exc:
        raise RobomodelError(str(exc)) from None
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark
        where = f"{path}:{mark.line + 1}:{mark.column + 1}" if mark else str(path)
        raise RobomodelError(f"{where}: YAML syntax error: {exc.problem}") from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise RobomodelError(f"{path}: a parameter file is a mapping of node names")
    out: dict[str, Any] = {}
    for key, section in data.items():
        if not isinstance(section, dict) or not _matches(str(key), fqn):
            continue
        params = section.get("ros__parameters")
        if isinstance(params, dict):
            out.update(flatten(params))
    return out
