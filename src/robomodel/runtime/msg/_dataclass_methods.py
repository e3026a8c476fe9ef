"""``__init__`` and ``__repr__`` of message classes made at run time, in time linear in their
fields.

``dataclasses`` writes both as source and compiles it: ``__init__`` with every default and
type as a closure variable of a wrapper function, ``__repr__`` as one f-string of every field.
CPython compiles either in time that grows with the square of the fields (a class of 8,000
fields took 7 s, of which 0.2 s remained without these two). The methods here behave as the
dataclass ones (the same parameters, order, defaults and factories; the same text): the
defaults are the function's ``__defaults__`` and the factories module globals of the
compiled code, and ``__repr__`` is a loop.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import MISSING, Field
from typing import Any

__all__ = ["add_init_and_repr"]


class _Factory:
    """The default of a parameter whose value is made by a factory (dataclasses'
    ``_HAS_DEFAULT_FACTORY``)."""

    __slots__ = ()

    def __repr__(self) -> str:
        return "<factory>"


_FACTORY = _Factory()


def _fresh(name: str, taken: Sequence[str]) -> str:
    while name in taken:
        name = f"_{name}"
    return name


def add_init_and_repr(cls: Any) -> None:
    """Give ``cls`` (a dataclass made with ``init=False, repr=False``) the ``__init__`` and
    ``__repr__`` that dataclasses would have given it."""
    fields: tuple[Field[Any], ...] = dataclasses.fields(cls)
    names = tuple(f.name for f in fields)
    # the method's own names, chosen apart from every field's (a learned definition may use any)
    self_name, sentinel, factories = (_fresh(n, names) for n in ("self", "_FACTORY", "_FACTORIES"))
    namespace: dict[str, Any] = {sentinel: _FACTORY, factories: [f.default_factory for f in fields]}
    defaults: list[Any] = []
    body: list[str] = []
    for index, f in enumerate(fields):
        if f.default_factory is not MISSING:
            defaults.append(_FACTORY)
            made = f"{factories}[{index}]() if {f.name} is {sentinel} else {f.name}"
            body.append(f" {self_name}.{f.name} = {made}\n")
        elif f.default is MISSING:
            raise TypeError(f"{cls.__name__}.{f.name}: a message field needs a default")
        else:
            defaults.append(f.default)
            body.append(f" {self_name}.{f.name} = {f.name}\n")
    params = ", ".join((self_name, *names))
    source = f"def __init__({params}):\n{''.join(body) or ' pass'}\n"
    exec(compile(source, f"<{cls.__qualname__}.__init__>", "exec"), namespace)
    init: Callable[..., None] = namespace["__init__"]
    init.__defaults__ = tuple(defaults)
    init.__qualname__ = f"{cls.__qualname__}.__init__"
    init.__module__ = cls.__module__
    cls.__init__ = init

    def __repr__(self: Any) -> str:
        inner = ", ".join(f"{name}={getattr(self, name)!r}" for name in names)
        return f"{type(self).__qualname__}({inner})"

    __repr__.__qualname__ = f"{cls.__qualname__}.__repr__"
    cls.__repr__ = __repr__
