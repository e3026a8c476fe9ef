"""``yaml.safe_load`` for text a user types or a peer sends: deep nesting is a clear error.

PyYAML composes nested collections recursively, so a value nested a few thousand levels deep
(``[[[[...]]]]``) raises RecursionError from inside the library. :func:`load_yaml` turns that
into :class:`YamlNestingError`, and refuses a document whose expansion through aliases is
larger than the parameter bound (a "billion laughs"), so the caller prints one line.

:func:`load_yaml_data` is stricter, for files of data that a program wrote (a bag's
``metadata.yaml``): aliases are refused and nesting is bounded by ``MAX_DATA_DEPTH``, both checked
on the parser's events before anything is built (libyaml's parser keeps its own stack, so even
50,000 levels cannot overflow Python's).

:func:`check_yaml_file` and :func:`load_yaml_file` are for files a user names (an ``.rviz``
config, controller YAML, a parameter file): aliases are allowed, as the tools these files come
from allow them, but the document is bounded on the parser's events before anything is built:
its size in bytes (``MAX_FILE_BYTES``), its nesting (``MAX_FILE_DEPTH``, aliases counted at the
depth they expand to) and its number of nodes once every alias is expanded
(``MAX_EXPANDED_NODES``: a 368-byte file of nested aliases expands to billions). The error
carries the file, line and column.
"""

from __future__ import annotations

from typing import Any

from robomodel.errors import RobomodelError

__all__ = [
    "MAX_DATA_DEPTH",
    "MAX_EXPANDED_NODES",
    "MAX_FILE_BYTES",
    "MAX_FILE_DEPTH",
    "YamlNestingError",
    "check_yaml_file",
    "load_yaml",
    "load_yaml_data",
    "load_yaml_file",
]

MAX_DATA_DEPTH = 64  # rosbag2's metadata.yaml nests 6 levels deep
MAX_FILE_BYTES = 16 * 1024 * 1024  # an .rviz file is a few KiB, a big controller YAML ~100 KiB
MAX_FILE_DEPTH = 100  # RViz configs nest about 8 levels, parameter files about 10
MAX_EXPANDED_NODES = 1_000_000  # collections and scalars, every alias expanded


class YamlNestingError(RobomodelError, ValueError):
    """YAML nested too deeply, or expanding through aliases beyond the bound.

    Attributes:
        path, line, column: Where (1-based; 0 when unknown).
        problem: What is wrong, without the place.
    """

    def __init__(
        self, message: str, *, path: str = "", line: int = 0, column: int = 0, problem: str = ""
    ) -> None:
        super().__init__(message)
        self.path = path
        self.line = line
        self.column = column
        self.problem = problem or message


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


def check_yaml_file(
    text: str,
    *,
    where: str,
    loader: Any = None,
    max_bytes: int = MAX_FILE_BYTES,
    max_depth: int = MAX_FILE_DEPTH,
    max_nodes: int = MAX_EXPANDED_NODES,
) -> None:
    """Refuse ``text`` (the contents of ``where``) past the size, nesting or expansion bound,
    before anything is built. A syntax error is left for the load that follows to place.

    Raises:
        YamlNestingError: ``where:line:column: ...``, one line.
    """
    import yaml

    def refuse(mark: Any, problem: str) -> YamlNestingError:
        line, column = (mark.line + 1, mark.column + 1) if mark is not None else (0, 0)
        at = f"{where}:{line}:{column}" if mark is not None else where
        return YamlNestingError(
            f"{at}: {problem}", path=where, line=line, column=column, problem=problem
        )

    size = len(text) if len(text) * 4 <= max_bytes else len(text.encode("utf-8", "surrogatepass"))
    if size > max_bytes:
        problem = f"{size} bytes, larger than the {max_bytes} bytes a YAML file may be"
        raise YamlNestingError(f"{where}: {problem}", path=where, problem=problem)
    if loader is None:
        loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    # One frame per open collection: [nodes inside it, deepest level inside it, its anchor].
    frames: list[list[Any]] = [[0, 0, None]]
    anchors: dict[str, tuple[int, int]] = {}  # anchor -> (expanded nodes, levels inside)
    total = 0
    try:
        for event in yaml.parse(text, Loader=loader):
            if isinstance(event, yaml.CollectionStartEvent):
                frames.append([1, 1, event.anchor])
                if len(frames) - 1 > max_depth:
                    raise refuse(event.start_mark, f"nested more than {max_depth} levels deep")
                continue
            if isinstance(event, yaml.CollectionEndEvent):
                nodes, depth, anchor = frames.pop()
                if anchor is not None:
                    anchors[anchor] = (nodes, depth)
            elif isinstance(event, yaml.ScalarEvent):
                nodes, depth = 1, 0
                if event.anchor is not None:
                    anchors[event.anchor] = (1, 0)
            elif isinstance(event, yaml.AliasEvent):
                nodes, depth = anchors.get(event.anchor or "", (1, 0))
                if len(frames) - 1 + depth > max_depth:
                    raise refuse(
                        event.start_mark,
                        f"the alias *{event.anchor} expands to more than {max_depth} levels deep",
                    )
            else:
                continue
            parent = frames[-1]
            parent[0] += nodes
            parent[1] = max(parent[1], depth + 1)
            total += nodes if isinstance(event, yaml.AliasEvent) else 1
            if total > max_nodes or parent[0] > max_nodes:
                raise refuse(
                    event.start_mark,
                    f"more than {max_nodes} values once its aliases are expanded "
                    "(aliases repeating a block?)",
                )
    except yaml.YAMLError:
        return  # the load places it


def load_yaml_file(
    text: str,
    *,
    where: str,
    loader: Any = None,
    max_bytes: int = MAX_FILE_BYTES,
    max_depth: int = MAX_FILE_DEPTH,
    max_nodes: int = MAX_EXPANDED_NODES,
) -> Any:
    """``yaml.load(text, loader)`` (a safe loader by default) within the bounds of
    :func:`check_yaml_file`.

    Raises:
        yaml.YAMLError: a syntax error (for the caller to place).
        YamlNestingError: past a bound, ``where:line:column: ...``.
    """
    import yaml

    check_yaml_file(
        text,
        where=where,
        loader=loader,
        max_bytes=max_bytes,
        max_depth=max_depth,
        max_nodes=max_nodes,
    )
    if loader is None:
        loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    try:
        return yaml.load(text, Loader=loader)
    except RecursionError:
        problem = "nested too deeply for YAML"
        raise YamlNestingError(f"{where}: {problem}", path=where, problem=problem) from None
