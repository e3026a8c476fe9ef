"""The field type descriptions of a rosidl-flavoured class's ``SLOT_TYPES``, named and shaped as
rosidl_parser's ``definition`` module has them (``BasicType('double')``,
``UnboundedSequence(BasicType('double'))``, ``NamespacedType(['std_msgs', 'msg'], 'Header')``),
so that code walking ``SLOT_TYPES`` with ``isinstance`` against these names works."""

from __future__ import annotations

from typing import Any

__all__ = [
    "AbstractGenericString",
    "AbstractNestedType",
    "AbstractSequence",
    "AbstractString",
    "AbstractType",
    "Array",
    "BasicType",
    "BoundedSequence",
    "BoundedString",
    "NamespacedType",
    "UnboundedSequence",
    "UnboundedString",
]


class AbstractType:
    """Base of every type description; equal when of one class with equal fields."""

    __slots__ = ()

    def __eq__(self, other: object) -> bool:
        return type(self) is type(other) and all(
            getattr(self, s) == getattr(other, s) for s in _all_slots(type(self))
        )

    def __hash__(self) -> int:
        return hash(
            (type(self).__name__, *(repr(getattr(self, s)) for s in _all_slots(type(self))))
        )

    def __repr__(self) -> str:
        args = ", ".join(repr(getattr(self, s)) for s in _all_slots(type(self)))
        return f"{type(self).__name__}({args})"


def _all_slots(cls: type) -> tuple[str, ...]:
    return tuple(s for klass in reversed(cls.__mro__) for s in getattr(klass, "__slots__", ()))


class BasicType(AbstractType):
    """A primitive: ``boolean``, ``octet``, ``float``, ``double``, ``int8`` ... ``uint64``."""

    __slots__ = ("typename",)

    def __init__(self, typename: str) -> None:
        self.typename = typename


class NamespacedType(AbstractType):
    """A message type: ``namespaces`` (``['std_msgs', 'msg']``) and ``name``."""

    __slots__ = ("name", "namespaces")

    def __init__(self, namespaces: list[str], name: str) -> None:
        self.namespaces = list(namespaces)
        self.name = name

    def namespaced_name(self) -> tuple[str, ...]:
        return (*self.namespaces, self.name)


class AbstractGenericString(AbstractType):
    __slots__ = ()

    def has_maximum_size(self) -> bool:
        return False


class AbstractString(AbstractGenericString):
    __slots__ = ()


class UnboundedString(AbstractString):
    __slots__ = ()


class BoundedString(AbstractString):
    __slots__ = ("maximum_size",)

    def __init__(self, maximum_size: int) -> None:
        self.maximum_size = maximum_size

    def has_maximum_size(self) -> bool:
        return True


class AbstractNestedType(AbstractType):
    """An array or a sequence of ``value_type``."""

    __slots__ = ("value_type",)

    def __init__(self, value_type: Any) -> None:
        self.value_type = value_type

    def has_maximum_size(self) -> bool:
        return False


class Array(AbstractNestedType):
    __slots__ = ("size",)

    def __init__(self, value_type: Any, size: int) -> None:
        super().__init__(value_type)
        self.size = size

    def has_maximum_size(self) -> bool:
        return True


class AbstractSequence(AbstractNestedType):
    __slots__ = ()


class UnboundedSequence(AbstractSequence):
    __slots__ = ()


class BoundedSequence(AbstractSequence):
    __slots__ = ("maximum_size",)

    def __init__(self, value_type: Any, maximum_size: int) -> None:
        super().__init__(value_type)
        self.maximum_size = maximum_size

    def has_maximum_size(self) -> bool:
        return True
