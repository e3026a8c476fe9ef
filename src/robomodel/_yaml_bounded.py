"""``yaml.safe_load`` for text a user types or a peer sends: deep nesting is a clear error.

PyYAML composes nested collections recursively, so a value nested a few thousand levels deep
(``[[[[...]]]]``) raises RecursionError from inside the library. :func:`load_yaml` turns that
into :class:`YamlNestingError`, and refuses a document whose expansion through aliases is
larger than the parameter bound (a "billion laughs"), so the caller prints one line.

:func:`load_yaml_data` is stricter, for files of data that a program wrote (a bag's
``metadata.yaml``): aliases are refused and nesting is bounded by ``MAX_DATA_DEPTH``, both checked
on the parser's events before anything is built (libyaml's parser keeps its own stack, so even
50,000 levels cannot overflow Python's).
"""

from __future__ import annotations

from typing import Any

from robomodel.errors import RobomodelError

__all__ = ["MAX_DATA_DEPTH", "YamlNestingError", "load_yaml", "load_yaml_data"]

MAX_DATA_DEPTH = 64  # rosbag2's metadata.yaml nests 6 levels deep


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


def load_yaml_data(text: str, *, what: str, max_depth: int = MAX_DATA_DEPTH) -> Any:
    """``yaml.safe_load(text)`` for machine-written data: no aliases, at most ``max_depth``
    nested collections.

    Raises:
        yaml.YAMLError: a syntax error.
        YamlNestingError: an alias, or nesting deeper than ``max_depth`` (with its line).
    """
    import yaml

    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    depth = 0
    for event in yaml.parse(text, Loader=loader):
        line = event.start_mark.line + 1 if event.start_mark is not None else 0
        if isinstance(event, yaml.AliasEvent):
            raise YamlNestingError(
                f"{what}: line {line}: a YAML alias (*{event.anchor}); "
                "aliases are not accepted here, write the value out"
            )
        if isinstance(event, yaml.CollectionStartEvent):
            depth += 1
            if depth > max_depth:
                raise YamlNestingError(
                    f"{what}: line {line}: nested more than {max_depth} levels deep"
                )
        elif isinstance(event, yaml.CollectionEndEvent):
            depth -= 1
    return yaml.load(text, Loader=loader)  # a safe loader; aliases and depth checked above
