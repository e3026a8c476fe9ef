"""The rosidl flavour: message classes as rosidl_generator_py generates them for rclpy.

Transcribed from rosidl_generator_py's ``resource/_msg.py.em`` (github:ros2/rosidl_python,
commit 4b5dfcf): a keyword-only constructor; every field a property over an underscored slot
(``_data``) whose setter checks the value with rosidl's assertion and message when field checks
are on (``check_fields=``, else ``ROS_PYTHON_CHECK_FIELDS``; robomodel checks unless that is
``0``, as rclpy before Jazzy did) and converts it to rosidl's container: ``array.array`` for a
numeric sequence, a numpy array for a fixed-size numeric array, ``bytes`` of length 1 for an
``octet`` (``byte``) and a list of them for ``byte[]``; ``char`` is rosidl's ``uint8``.
``__repr__`` (``std_msgs.msg.String(data='x')``), ``__eq__``, ``get_fields_and_field_types()``,
``SLOT_TYPES`` (:mod:`.slot_types`) and the constants as class attributes are rosidl's.

The decoders build instances through ``__from_fields__``: the wire's values converted to the
containers with no checks, as rclpy's C conversion does.
"""

from __future__ import annotations

import array
import math
import os
from collections import UserList, UserString
from collections.abc import ByteString, Sequence, Set
from typing import TYPE_CHECKING, Any

from robomodel.clientlibs.messages import slot_types
from robomodel.runtime.msg._source_gen import SourceGen
from robomodel.runtime.msg.schema import Array, Message, Seq, Spec

__all__ = ["FLAVOUR", "RosidlFlavour", "RosidlMessage", "rosidl_type"]

# rosidl_generator_py's SPECIAL_NESTED_BASIC_TYPES by robomodel's primitive names (a .msg
# ``char`` is IDL ``uint8``): array.array type code and numpy dtype.
_SPECIAL = {
    "float32": ("f", "float32"),
    "float64": ("d", "float64"),
    "int8": ("b", "int8"),
    "uint8": ("B", "uint8"),
    "char": ("B", "uint8"),
    "int16": ("h", "int16"),
    "uint16": ("H", "uint16"),
    "int32": ("i", "int32"),
    "uint32": ("I", "uint32"),
    "int64": ("q", "int64"),
    "uint64": ("Q", "uint64"),
}
# IDL names of robomodel's primitives (rosidl_adapter's MSG_TYPE_TO_IDL)
_IDL = {
    "bool": "boolean",
    "byte": "octet",
    "char": "uint8",
    "float32": "float",
    "float64": "double",
}
_FLOAT_BOUND = {"float32": 3.402823466e38, "float64": 1.7976931348623157e308}
_FLOAT_NAME = {"float32": "float", "float64": "double"}


# Read once, as the generated modules read ROS_PYTHON_CHECK_FIELDS when imported.
_CHECK_DEFAULT = os.environ.get("ROS_PYTHON_CHECK_FIELDS", "1") != "0"


def _check_default() -> bool:
    return _CHECK_DEFAULT


class RosidlMessage:
    """Base of the rosidl-flavoured classes: what every generated class has alike."""

    if TYPE_CHECKING:  # each class has its fields' slots and this one
        __slots__ = ("_check_fields",)
    else:
        __slots__ = ()
    _fields_and_field_types: dict[str, str]
    SLOT_TYPES: tuple[Any, ...]

    def __init__(self, **kwargs: Any) -> None:
        """Generated per class (:meth:`RosidlFlavour.finish`): the given fields through their
        setters, the others their defaults."""
        raise NotImplementedError(f"{type(self).__name__} was not finished by its flavour")

    def _unknown_arguments(self, kwargs: dict[str, Any]) -> None:
        unknown = [k for k in kwargs if k not in self._fields_and_field_types]
        if unknown:  # rosidl asserts; raised so that python -O keeps the check
            raise AssertionError(
                f"Invalid arguments passed to constructor: {', '.join(sorted(unknown))}"
            )

    def __repr__(self) -> str:
        typename = [*type(self).__module__.split("."), type(self).__name__]
        args = []
        for s, t in zip(self._fields_and_field_types, self.SLOT_TYPES, strict=True):
            value = getattr(self, s)
            text = repr(value)
            if (
                isinstance(t, slot_types.AbstractSequence)
                and isinstance(t.value_type, slot_types.BasicType)
                and isinstance(value, array.array)
            ):
                text = "[]" if len(value) == 0 else text[len("array('X', ") : -len(")")]
            args.append(f"{s}={text}")
        return f"{'.'.join(typename)}({', '.join(args)})"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, self.__class__):
            return False
        for name in self._fields_and_field_types:
            mine, theirs = getattr(self, name), getattr(other, name)
            if _is_ndarray(mine) or _is_ndarray(theirs):
                import numpy

                if not numpy.array_equal(mine, theirs):
                    return False
            elif mine != theirs:
                return False
        return True

    __hash__ = None  # type: ignore[assignment]  # as rosidl's: __eq__ without __hash__

    @classmethod
    def get_fields_and_field_types(cls) -> dict[str, str]:
        return dict(cls._fields_and_field_types)

    def __reduce__(self) -> tuple[Any, ...]:
        state = {name: getattr(self, name) for name in self._fields_and_field_types}
        return rebuild, ("rosidl", type(self).__typename__, state)  # type: ignore[attr-defined]


def rebuild(flavour: str, typename: str, state: dict[str, Any]) -> Any:
    """A pickled flavoured message, made again in its flavour (``pkg.msg`` gives the
    process's flavour, which may be the other one)."""
    import sys

    messages = sys.modules["robomodel.clientlibs.messages"]  # loaded: it made the class
    found = messages.message_class(typename, flavour)
    message = found.__new__(found)
    for name, value in state.items():
        object.__setattr__(message, f"_{name}" if flavour == "rosidl" else name, value)
    if flavour == "rosidl":
        object.__setattr__(message, "_check_fields", _CHECK_DEFAULT)
    return message


def _is_ndarray(value: Any) -> bool:
    return type(value).__name__ == "ndarray"


def rosidl_type(spec: Spec) -> str:
    """The type of a field as ``get_fields_and_field_types()`` names it
    (``sequence<double>``, ``double[9]``, ``std_msgs/Header``, ``string<10>``)."""
    if isinstance(spec, Seq):
        bound = f", {spec.bound}" if spec.bound is not None else ""
        return f"sequence<{rosidl_type(spec.item)}{bound}>"
    if isinstance(spec, Array):
        return f"{rosidl_type(spec.item)}[{spec.size}]"
    if isinstance(spec, str):
        base, _, bound = spec.partition("<=")
        if base == "string":
            return f"string<{bound}>" if bound else "string"
        return _IDL.get(base, base)
    package, _, name = spec.__typename__.split("/")
    return f"{package}/{name}"


def _slot_type(spec: Spec) -> Any:
    if isinstance(spec, Seq):
        item = _slot_type(spec.item)
        if spec.bound is None:
            return slot_types.UnboundedSequence(item)
        return slot_types.BoundedSequence(item, spec.bound)
    if isinstance(spec, Array):
        return slot_types.Array(_slot_type(spec.item), spec.size)
    if isinstance(spec, str):
        base, _, bound = spec.partition("<=")
        if base == "string":
            return slot_types.BoundedString(int(bound)) if bound else slot_types.UnboundedString()
        return slot_types.BasicType(_IDL.get(base, base))
    package, kind, name = spec.__typename__.split("/")
    return slot_types.NamespacedType([package, kind], name)


class _Gen(SourceGen):
    def __init__(self) -> None:
        super().__init__(
            {
                "_array": array.array,
                "_isinf": math.isinf,
                "Sequence": Sequence,
                "Set": Set,
                "UserList": UserList,
                "UserString": UserString,
                "ByteString": ByteString,
                "_octets": _split_octets,
                "_u8": _uint8_ndarray,
                "_np": _numpy,
            }
        )


def _numpy() -> Any:
    import numpy

    return numpy


def _split_octets(value: Any) -> list[Any]:
    """``byte[]`` values from the wire (bytes) as rosidl's list of bytes of length 1."""
    if isinstance(value, (bytes, bytearray)):
        return [value[i : i + 1] for i in range(len(value))]
    return list(value)


def _uint8_ndarray(value: Any) -> Any:
    numpy = _numpy()
    if isinstance(value, (bytes, bytearray, memoryview)):
        return numpy.frombuffer(value, numpy.uint8).copy()
    return numpy.array(value, dtype=numpy.uint8)


def _kind(spec: Spec) -> str:
    """How a field is held: 'seq' (array.array), 'ndarray', 'octet', 'octets', or 'plain'."""
    if isinstance(spec, (Seq, Array)) and isinstance(spec.item, str):
        if spec.item in _SPECIAL:
            return "seq" if isinstance(spec, Seq) else "ndarray"
        if spec.item == "byte":
            return "octets"
    if spec == "byte":
        return "octet"
    return "plain"


def _to_container(g: _Gen, spec: Spec, value: str) -> str:
    """The expression converting ``value`` to the field's container (no check)."""
    kind = _kind(spec)
    if kind == "seq":
        return f"_array('{_SPECIAL[spec.item][0]}', {value})"  # type: ignore[union-attr,index]
    if kind == "ndarray":
        dtype = _SPECIAL[spec.item][1]  # type: ignore[union-attr,index]
        if dtype == "uint8":
            return f"_u8({value})"
        return f"_np().array({value}, dtype='{dtype}')"
    if kind == "octets":
        return f"_octets({value})"
    if kind == "octet":
        return f"({value} if {value}.__class__ is bytes else bytes(({value},)))"
    return value


def _default(g: _Gen, spec: Spec) -> str:
    """The expression of a field's default, as rosidl's constructor makes it."""
    kind = _kind(spec)
    if kind == "seq":
        return f"_array('{_SPECIAL[spec.item][0]}')"  # type: ignore[union-attr,index]
    if kind == "ndarray":
        dtype = _SPECIAL[spec.item][1]  # type: ignore[union-attr,index]
        return f"_np().zeros({spec.size}, dtype='{dtype}')"  # type: ignore[union-attr]
    if kind == "octets":
        return "[]" if isinstance(spec, Seq) else f"[b'\\x00'] * {spec.size}"  # type: ignore[union-attr]
    if kind == "octet":
        return "b'\\x00'"
    if isinstance(spec, Seq):
        return "[]"
    if isinstance(spec, Array):
        return f"[{_default(g, spec.item)} for _ in range({spec.size})]"
    if isinstance(spec, str):
        base = spec.partition("<=")[0]
        return {"string": "''", "bool": "False", "float32": "0.0", "float64": "0.0"}.get(base, "0")
    return f"{g.ref(spec, 'T')}()"


def _raising(line: str) -> str:
    """rosidl's ``assert cond, "The ..."`` as an ``if``/``raise AssertionError``: the same
    exception and message, kept under ``python -O``."""
    indent = line[: len(line) - len(line.lstrip())]
    body = line.lstrip()
    if not body.startswith("assert "):
        return line
    condition, message = body[len("assert ") :].rsplit(', "The ', 1)
    return f'{indent}if not ({condition}): raise AssertionError("The {message})'


def _check(g: _Gen, name: str, spec: Spec) -> list[str]:
    """rosidl's assertion lines for a value of field ``name`` (``value``), run when checks
    are on; the messages are rosidl's."""
    if isinstance(spec, (Seq, Array)):
        return _check_nested(g, name, spec)
    if isinstance(spec, str):
        base, _, bound = spec.partition("<=")
        if base == "string":
            if bound:
                return [
                    f"assert isinstance(value, (str, UserString)) and len(value) <= {bound}, "
                    f"\"The '{name}' field must be string value not longer than {bound}\""
                ]
            return [f"assert isinstance(value, str), \"The '{name}' field must be of type 'str'\""]
        if base == "byte":
            return [
                "assert isinstance(value, (bytes, ByteString)) and len(value) == 1, "
                f"\"The '{name}' field must be of type 'bytes' or 'ByteString' with length 1\""
            ]
        return _check_number(name, base)
    type_name = spec.__name__
    return [
        f"assert isinstance(value, {g.ref(spec, 'T')}), "
        f"\"The '{name}' field must be a sub message of type '{type_name}'\""
    ]


def _check_number(name: str, base: str) -> list[str]:
    if base == "bool":
        return [f"assert isinstance(value, bool), \"The '{name}' field must be of type 'bool'\""]
    if base in _FLOAT_BOUND:
        bound = _FLOAT_BOUND[base]
        lines = [f"assert isinstance(value, float), \"The '{name}' field must be of type 'float'\""]
        if base == "float32":  # every Python float is in a double's range, or infinite
            lines.append(
                f"assert not (value < -{bound!r} or value > {bound!r}) or _isinf(value), "
                f"\"The '{name}' field must be a {_FLOAT_NAME[base]} in [-{bound!r}, {bound!r}]\""
            )
        return lines
    unsigned = base.startswith("uint") or base == "char"
    bits = 8 if base == "char" else int(base.removeprefix("u").removeprefix("int"))
    lines = [f"assert isinstance(value, int), \"The '{name}' field must be of type 'int'\""]
    if unsigned:
        lines.append(
            f"assert value >= 0 and value < {2**bits}, "
            f"\"The '{name}' field must be an unsigned integer in [0, {2**bits - 1}]\""
        )
    else:
        half = 2 ** (bits - 1)
        lines.append(
            f"assert value >= -{half} and value < {half}, "
            f"\"The '{name}' field must be an integer in [-{half}, {half - 1}]\""
        )
    return lines


def _check_nested(g: _Gen, name: str, spec: Seq | Array) -> list[str]:
    item = spec.item
    lines: list[str] = []
    kind = _kind(spec)
    if kind == "ndarray":
        dtype = _SPECIAL[item][1]  # type: ignore[index]
        lines += [
            "if _np_ndarray(value):",
            f"    assert value.dtype == '{dtype}', \"The '{name}' numpy.ndarray() must have the"
            f" dtype of 'numpy.{dtype}'\"",
            f"    assert value.size == {spec.size}, \"The '{name}' numpy.ndarray() must have a"  # type: ignore[union-attr]
            f' size of {spec.size}"',  # type: ignore[union-attr]
            f"    self._{name} = value",
            "    return",
        ]
    elif kind == "seq":
        code = _SPECIAL[item][0]  # type: ignore[index]
        lines += [
            "if isinstance(value, _array):",
            f"    assert value.typecode == '{code}', \"The '{name}' array.array() must have the"
            f" type code of '{code}'\"",
        ]
        if isinstance(spec, Seq) and spec.bound is not None:
            lines.append(
                f"    assert len(value) <= {spec.bound}, \"The '{name}' array.array() must have"
                f' a size <= {spec.bound}"'
            )
        lines += [f"    self._{name} = value", "    return"]
    conditions = [  # a list or tuple first: the ABCs' isinstance is the slow part
        "(value.__class__ is list or value.__class__ is tuple or ((isinstance(value, Sequence)"
        " or isinstance(value, Set) or isinstance(value, UserList)) and not isinstance(value,"
        " str) and not isinstance(value, UserString)))",
    ]
    suffixes = ["a set or sequence"]
    if isinstance(spec, Seq) and spec.bound is not None:
        conditions.append(f"len(value) <= {spec.bound}")
        suffixes.append(f"with length <= {spec.bound}")
    elif isinstance(spec, Array):
        conditions.append(f"len(value) == {spec.size}")
        suffixes.append(f"with length {spec.size}")
    python_type, extra, extra_text = _item_check(g, item)
    if isinstance(item, str) and item.startswith("string<="):
        bound = item.partition("<=")[2]
        conditions.append(f"all(len(val) <= {bound} for val in value)")
        suffixes.append(f"and each string value not longer than {bound}")
    conditions.append(f"all(isinstance(v, {python_type[0]}) for v in value)")
    suffixes.append(f"and each value of type '{python_type[1]}'")
    if extra:
        conditions.append(extra)
        suffixes.append(extra_text)
    lines.append(
        f"assert ({' and '.join(conditions)}), \"The '{name}' field must be {' '.join(suffixes)}\""
    )
    return lines


def _item_check(g: _Gen, item: Spec) -> tuple[tuple[str, str], str, str]:
    """(isinstance target and its name, the range condition and its text) of sequence items."""
    if isinstance(item, type):
        return (g.ref(item, "T"), item.__name__), "", ""
    if not isinstance(item, str):
        raise TypeError(f"an array of arrays is not a ROS field type: {item!r}")
    base = item.partition("<=")[0]
    if base == "string":
        return ("str", "str"), "", ""
    if base == "byte":
        return ("bytes", "bytes"), "", ""
    if base == "bool":
        return ("bool", "bool"), "", ""
    if base in _FLOAT_BOUND:
        bound = _FLOAT_BOUND[base]
        # a double's range holds every Python float (or it is infinite): the message only
        in_range = (
            "True"
            if base == "float64"
            else (f"all(not (val < -{bound!r} or val > {bound!r}) or _isinf(val) for val in value)")
        )
        return (
            ("float", "float"),
            in_range,
            f"and each {_FLOAT_NAME[base]} in [{-bound:f}, {bound:f}]",
        )
    bits = 8 if base == "char" else int(base.removeprefix("u").removeprefix("int"))
    if base.startswith("uint") or base == "char":
        return (
            ("int", "int"),
            f"all(val >= 0 and val < {2**bits} for val in value)",
            f"and each unsigned integer in [0, {2**bits - 1}]",
        )
    half = 2 ** (bits - 1)
    return (
        ("int", "int"),
        f"all(val >= -{half} and val < {half} for val in value)",
        f"and each integer in [-{half}, {half - 1}]",
    )


class RosidlFlavour:
    """rclpy's classes (see the module's docstring); a :class:`MessageFlavour`."""

    name = "rosidl"

    def class_name(self, name: str) -> str:
        return name.rsplit("/", 1)[-1]

    def class_body(
        self,
        name: str,
        specs: tuple[tuple[str, Spec], ...],
        constants: tuple[tuple[str, str, Any], ...],
    ) -> tuple[tuple[type, ...], dict[str, Any]]:
        body: dict[str, Any] = {
            "__slots__": (*(f"_{n}" for n, _ in specs), "_check_fields"),
            "_fields_and_field_types": {n: rosidl_type(s) for n, s in specs},
            "SLOT_TYPES": tuple(_slot_type(s) for _, s in specs),
        }
        return (RosidlMessage,), body

    def finish(self, cls: type[Message]) -> None:
        """Generate the field properties, ``__defaults__`` and ``__from_fields__``."""
        g = _Gen()
        g.env["_np_ndarray"] = _is_ndarray
        g.env["_check_default"] = _check_default
        g.env["_new"] = object.__new__
        g.env["_cls"] = cls
        names = [n for n, _ in cls.__fields__]
        annotated = cls.__dict__.get("__field_defaults__", {})
        for name, spec in cls.__fields__:
            g.emit(0, f"def _get_{name}(self):")
            g.emit(1, f"return self._{name}")
            g.emit(0, f"def _set_{name}(self, value):")
            g.emit(1, "if self._check_fields:")
            for line in _check(g, name, spec):
                g.emit(2, _raising(line))
            g.emit(1, f"self._{name} = {_to_container(g, spec, 'value')}")
            g.emit(0, f"def _default_{name}():")
            if name in annotated:  # the definition's default annotation
                g.emit(1, f"return {annotated[name]!r}")
            else:
                g.emit(1, f"return {_default(g, spec)}")
        # rosidl's constructor: given fields through their setters, the others their defaults
        g.emit(0, "def __init__(self, **kwargs):")
        g.emit(1, f"self._check_fields = kwargs.pop('check_fields', {_CHECK_DEFAULT})")
        g.emit(1, "if kwargs and self._check_fields: self._unknown_arguments(kwargs)")
        for name in names:
            g.emit(1, f"if '{name}' in kwargs: self.{name} = kwargs['{name}']")
            g.emit(1, f"else: self._{name} = _default_{name}()")
        params = ", ".join(f"{n}=_MISSING" for n in names)
        g.env["_MISSING"] = _MISSING
        g.emit(0, f"def __from_fields__({params}):")
        g.emit(1, "_o = _new(_cls)")  # ROS field names never start with "_"
        g.emit(1, f"_o._check_fields = {_CHECK_DEFAULT}")
        for name, spec in cls.__fields__:
            g.emit(1, f"if {name} is _MISSING: _o._{name} = _default_{name}()")
            g.emit(1, f"else: _o._{name} = {_to_container(g, spec, name)}")
        g.emit(1, "return _o")
        exec("\n".join(g.lines), g.env)
        for name in names:
            prop = property(
                g.env[f"_get_{name}"], g.env[f"_set_{name}"], doc=f"Message field '{name}'."
            )
            setattr(cls, name, prop)
        setattr(cls, "__init__", g.env["__init__"])  # noqa: B010  # generated per class
        cls.__defaults__ = {n: g.env[f"_default_{n}"] for n in names}  # type: ignore[attr-defined]
        cls.__from_fields__ = staticmethod(g.env["__from_fields__"])  # type: ignore[attr-defined]


_MISSING: Any = object()
FLAVOUR = RosidlFlavour()
