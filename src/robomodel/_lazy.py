"""Lazy re-exports of a package's names (PEP 562): a name's module is imported on first use."""

from __future__ import annotations

import importlib
import sys
import types

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (mypy knows the name)
if TYPE_CHECKING:
    from collections.abc import Callable, Mapping, Sequence

# package -> its exported names that are also the names of the submodules defining them
_OVER_SUBMODULES: dict[str, frozenset[str]] = {}


class _ExportsOverSubmodules(types.ModuleType):
    """A package that exports a name its defining submodule also has (the description layer's
    ``validate``, from ``robomodel.description.validate``). Loading a submodule sets the
    package's attribute of that name to the submodule (the import system does), which would
    hide the export from then on, whoever loaded it; the export is kept instead, as an eager
    ``from .validate import validate`` in the package would have left it."""

    def __setattr__(self, name: str, value: object) -> None:
        if (
            isinstance(value, types.ModuleType)
            and value.__name__ == f"{self.__name__}.{name}"
            and name in _OVER_SUBMODULES.get(self.__name__, ())
        ):
            value = getattr(value, name)
        super().__setattr__(name, value)


def lazy_exports(
    package: str, module_of: Mapping[str, str], namespace: dict[str, object], names: Sequence[str]
) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """The ``__getattr__`` and ``__dir__`` of ``package``: ``module_of`` maps each name to the
    module that defines it; ``namespace`` is the package's ``globals()``, where a name once
    imported is kept; ``names`` is its ``__all__``. Called while the package is being
    imported (it is in ``sys.modules``)."""
    over = frozenset(name for name, module in module_of.items() if module == f"{package}.{name}")
    if over:
        _OVER_SUBMODULES[package] = over
        sys.modules[package].__class__ = _ExportsOverSubmodules

    def __getattr__(name: str) -> object:
        module = module_of.get(name)
        if module is None:
            raise AttributeError(f"module '{package}' has no attribute '{name}'")
        value = getattr(importlib.import_module(module), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted({*namespace, *names})

    return __getattr__, __dir__
