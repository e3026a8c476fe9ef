"""``yaml.safe_load`` for text a user types or a peer sends: deep nesting is a clear error.

PyYAML composes nested collections recursively, so a value nested a few thousand levels deep
(``[[[[...]]]]``) raises RecursionError from inside the library. :func:`load_yaml` turns that
into :class:`YamlNestingError`, and refuses a document whose expansion through aliases is
larger than the parameter bound (a "billion laughs"), so the caller prints one line.
"""

from __future__ import annotations

from typing import Any

from robomodel.errors import RobomodelError

__all__ = ["YamlNestingError", "load_yaml"]


class YamlNestingError(RobomodelError, ValueError):
    """YAML nested too deeply, or expanding through aliases beyond the bound."""


def load_yaml(text: str, *, what: str = "the YAML value") -> Any:
    """``yaml.safe_load(text)``; deep nesting or alias bombs raise YamlNestingError.

    Raises:
        yaml.YAMLError: a syntax error (for the caller to place).
        YamlNestingError: nested too deeply, or too large once aliases are expanded.
    """
    import yaml

    from robomodel.runtime.transport.ros1.param_bounds import ParamBoundError, expand_bounded

    try:
        data = yaml.safe_load(text)
    except RecursionError:
        raise YamlNestingError(
            f"{what} is nested too deeply for YAML (a few hundred levels at most)"
        ) from None
    try:
        return expand_bounded(data, what=what) if isinstance(data, dict | list) else data
    except ParamBoundError as exc:
        raise YamlNestingError(str(exc)) from None
