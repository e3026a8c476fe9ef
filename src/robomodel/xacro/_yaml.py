"""``xacro.load_yaml``: YAML with unit tags and dotted access (reference L81-L140)."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (start-up)
if TYPE_CHECKING:
    from typing import Any

    import yaml

__all__ = ["UNIT_TAGS", "YamlDictWrapper", "YamlListWrapper", "load_yaml_text", "wrap"]

#: Unit tags and their factor to the SI base unit (radians, meters), as ``ConstructUnits``.
UNIT_TAGS: dict[str, float] = {
    "!radians": 1.0,
    "!degrees": math.pi / 180.0,
    "!meters": 1.0,
    "!millimeters": 0.001,
    "!foot": 0.3048,
    "!inches": 0.0254,
}


def wrap(item: Any) -> Any:
    """Wrap dicts and lists so that nested values keep dotted access."""
    if isinstance(item, dict):
        return YamlDictWrapper(item)
    if isinstance(item, list):
        return YamlListWrapper(item)
    return item


class YamlListWrapper(list["Any"]):
    """A YAML list whose items are wrapped on access."""

    def __getitem__(self, idx: Any) -> Any:
        return wrap(super().__getitem__(idx))

    def __iter__(self) -> Iterator[Any]:
        for item in super().__iter__():
            yield wrap(item)


class YamlDictWrapper(dict["Any", "Any"]):
    """A YAML mapping with dotted access (``settings.arm.length``); also ``xacro.dotify``."""

    def __getattr__(self, item: str) -> Any:
        try:
            return wrap(super().__getitem__(item))
        except KeyError:
            raise AttributeError(f"The yaml dictionary has no key '{item}'") from None

    __getitem__ = __getattr__


def _loader(evaluate_unit: Callable[[str], object]) -> type[yaml.SafeLoader]:
    """A SafeLoader subclass with the unit tags, so that the global SafeLoader stays untouched."""
    import yaml  # not at the top: only files that call xacro.load_yaml pay for it

    class Loader(yaml.SafeLoader):
        pass

    for tag, factor in UNIT_TAGS.items():

        def construct(loader: yaml.SafeLoader, node: yaml.Node, factor: float = factor) -> float:
            value = loader.construct_scalar(node)  # type: ignore[arg-type]
            return float(evaluate_unit(str(value))) * factor  # type: ignore[arg-type]

        Loader.add_constructor(tag, construct)
    return Loader


def load_yaml_text(
    text: str, evaluate_unit: Callable[[str], object], *, where: str = "the YAML text"
) -> Any:
    """Parse YAML text; unit-tagged scalars are xacro expressions (``!degrees 2*90``). Size,
    nesting and alias expansion are bounded (:func:`robomodel._yaml_bounded.load_yaml_file`).

    Raises:
        YamlNestingError: past a bound, ``where:line:column: ...``.
    """
    from robomodel._yaml_bounded import load_yaml_file

    return wrap(load_yaml_file(text, where=where, loader=_loader(evaluate_unit)))
