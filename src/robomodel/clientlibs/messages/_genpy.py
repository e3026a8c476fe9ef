"""The genpy flavour: message classes as genpy generates them for rospy.

After genpy's ``generator.py`` and ``message.py`` (github:ros/genpy): the fields are the slots
(``__slots__``, ``_slot_types``); the constructor takes every field positionally or any of them
by keyword, never both, and a field left out or ``None`` gets its default; ``_type``
(``std_msgs/String``), ``_md5sum``, ``_full_text`` and ``_has_header``; ``serialize(buff)`` and
``deserialize(str)`` in ROS 1's format (robomodel's ROS 1 codec), with the ``_numpy`` variants;
``str()`` and ``repr()`` as genpy's ``strify_message`` (YAML-like). ``uint8[]`` and ``char[]``
are ``bytes``; ``time`` and ``duration`` are genpy's ``Time`` and ``Duration``
(:mod:`._genpy_time`). Numeric arrays decode as lists (genpy gives tuples).
"""

from __future__ import annotations

from typing import Any

from robomodel.clientlibs.messages._genpy_time import DurationMixin, TimeMixin, TVal
from robomodel.runtime.msg._source_gen import SourceGen
from robomodel.runtime.msg.schema import Array, Message, Seq, Service, Spec, default_for

__all__ = [
    "FLAVOUR",
    "DeserializationError",
    "GenpyFlavour",
    "GenpyMessage",
    "MessageException",
    "SerializationError",
    "ros1_type_name",
    "strify_message",
]

TIME, DURATION = "builtin_interfaces/msg/Time", "builtin_interfaces/msg/Duration"


class MessageException(Exception):
    """genpy's base of message errors."""


class DeserializationError(MessageException):
    """Bytes that are not a message of the type (genpy's)."""


class SerializationError(MessageException):
    """A message whose values do not fit its fields (genpy's)."""


class _Ros1Attribute:
    """A class attribute computed from the type's ROS 1 description on first use
    (``_md5sum``, ``_full_text``): making a class does not load ROS 1's type store."""

    def __init__(self, attribute: str) -> None:
        self.attribute = attribute

    def __get__(self, obj: Any, owner: type) -> Any:
        return getattr(_ros1(owner), self.attribute)


def _ros1(cls: type) -> Any:
    """The ROS 1 type (name, md5sum, definition, codec) of a genpy-flavoured class."""
    from robomodel.runtime.transport.ros1.ros1_types import ros1_service_type, ros1_type

    if issubclass(cls, Service):
        return ros1_service_type(cls)
    service = cls.__dict__.get("_service_class")
    if service is not None:
        found = ros1_service_type(service)
        return found.request if cls is service.Request else found.response
    return ros1_type(cls)  # type: ignore[arg-type]


class GenpyMessage:
    """Base of the genpy-flavoured classes (genpy's ``Message``)."""

    __slots__ = ("_connection_header",)
    _type: str = ""
    _has_header = False
    _slot_types: list[str]
    __defaults__: dict[str, Any]

    def __init__(self, *args: Any, **kwds: Any) -> None:
        slots = self.__slots__
        if args and kwds:
            raise TypeError("Message constructor may only use args OR keywords, not both")
        if args:
            if len(args) != len(slots):
                raise TypeError(
                    f"Invalid number of arguments, args should be {list(slots)} args are{args}"
                )
            values = dict(zip(slots, args, strict=True))
        else:
            for key in kwds:
                if key not in slots:
                    raise AttributeError(f"{key} is not an attribute of {type(self).__name__}")
            values = kwds
        defaults = self.__defaults__
        for name in slots:
            value = values.get(name)
            setattr(self, name, defaults[name]() if value is None else value)

    def serialize(self, buff: Any) -> None:
        """Write the message in ROS 1's format to ``buff`` (a file-like object)."""
        try:
            buff.write(_ros1(type(self)).encode(self))
        except Exception as exc:  # genpy wraps every failure of its struct calls alike
            raise SerializationError(f"{type(self)._type}: {exc}") from exc

    def deserialize(self, str_: bytes) -> Any:
        """Read this message's fields from ROS 1's bytes; returns the message."""
        try:
            decoded = _ros1(type(self)).decode(str_)
        except Exception as exc:
            raise DeserializationError(str(exc)) from exc
        for name in self.__slots__:
            setattr(self, name, getattr(decoded, name))
        return self

    def serialize_numpy(self, buff: Any, numpy: Any) -> None:
        self.serialize(buff)

    def deserialize_numpy(self, str_: bytes, numpy: Any) -> Any:
        """As :meth:`deserialize`, with numeric arrays as numpy arrays (genpy's)."""
        self.deserialize(str_)
        for (name, spec), slot_type in zip(self.__fields__, self._slot_types, strict=True):  # type: ignore[attr-defined]
            if isinstance(spec, (Seq, Array)) and _numeric(spec.item) and "uint8[" not in slot_type:
                setattr(self, name, numpy.array(getattr(self, name), dtype=_dtype(spec.item)))
        return self

    def _get_types(self) -> list[str]:
        return self._slot_types

    def __reduce__(self) -> tuple[Any, ...]:
        from robomodel.clientlibs.messages._rosidl import rebuild

        state = {name: getattr(self, name) for name in self.__slots__}
        return rebuild, ("genpy", type(self).__typename__, state)  # type: ignore[attr-defined]

    def __getstate__(self) -> list[Any]:
        return [getattr(self, name) for name in self.__slots__]

    def __setstate__(self, state: list[Any]) -> None:
        for name, value in zip(self.__slots__, state, strict=True):
            setattr(self, name, value)

    def __repr__(self) -> str:
        return strify_message(self)

    def __str__(self) -> str:
        return strify_message(self)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, self.__class__):
            return False
        for name in self.__slots__:
            mine, theirs = getattr(self, name), getattr(other, name)
            if isinstance(mine, (list, tuple)) and isinstance(theirs, (list, tuple)):
                if tuple(mine) != tuple(theirs):  # genpy treats tuples and lists alike
                    return False
            elif not mine == theirs:
                return False
        return True

    def __ne__(self, other: object) -> bool:
        return not self == other

    __hash__ = None  # type: ignore[assignment]


def _numeric(item: Spec) -> bool:
    return (
        isinstance(item, str) and item not in ("string", "bool") and not item.startswith("string")
    )


def _dtype(item: Spec) -> str:
    return {"byte": "int8", "char": "uint8"}.get(str(item), str(item))


def ros1_type_name(spec: Spec) -> str:
    """A field's type as genpy's ``_slot_types`` names it (``std_msgs/Header``, ``float64[]``,
    ``time``)."""
    if isinstance(spec, Seq):
        return f"{ros1_type_name(spec.item)}[]"
    if isinstance(spec, Array):
        return f"{ros1_type_name(spec.item)}[{spec.size}]"
    if isinstance(spec, str):
        return spec.partition("<=")[0]
    if spec.__typename__ == TIME:
        return "time"
    if spec.__typename__ == DURATION:
        return "duration"
    package, _, name = spec.__typename__.split("/")
    return f"{package}/{name.replace('_', '')}"


def strify_message(val: Any, indent: str = "") -> str:
    """genpy's ``strify_message``: a message as YAML-like text."""
    if isinstance(val, bool) or type(val) in (int, float):
        return str(val)
    if isinstance(val, str):
        if not val:
            return "''"
        import yaml

        return str(yaml.dump(val, default_style='"')).rstrip("\n")
    if isinstance(val, TVal):
        return f"\n{indent}secs: {val.secs}\n{indent}nsecs: {val.nsecs:9d}"
    if type(val) in (list, tuple):
        if not val:
            return "[]"
        first = val[0]
        if isinstance(first, str):
            import yaml

            text = str(yaml.dump(list(val))).rstrip("\n")
            if text[0] == "[":
                return text
            return "\n" + "\n".join(indent + line for line in text.splitlines())
        if type(first) in (int, float, bool):
            return str(list(val))
        prefix, inner = indent + "- ", indent + "  "
        return "\n" + "\n".join(prefix + strify_message(v, inner) for v in val)
    if isinstance(val, GenpyMessage):
        lines = []
        for name, slot_type in zip(val.__slots__, val._slot_types, strict=True):
            value = getattr(val, name)
            if isinstance(value, (bytes, bytearray)) and "uint8[" in slot_type:
                value = list(value)
            lines.append(f"{indent}{name}: {strify_message(value, '  ' + indent)}")
        text = "\n".join(lines)
        return "\n" + text if indent else text
    return str(val)


class GenpyFlavour:
    """rospy's classes (see the module's docstring); a :class:`MessageFlavour`."""

    name = "genpy"

    def class_name(self, name: str) -> str:
        # pkg/srv/AddTwoInts_Request -> AddTwoIntsRequest, as genpy names a service's halves
        return name.rsplit("/", 1)[-1].replace("_", "")

    def class_body(
        self,
        name: str,
        specs: tuple[tuple[str, Spec], ...],
        constants: tuple[tuple[str, str, Any], ...],
    ) -> tuple[tuple[type, ...], dict[str, Any]]:
        package = name.split("/", 1)[0]
        header = (
            bool(specs)
            and specs[0][0] == "header"
            and _typename(specs[0][1]) == "std_msgs/msg/Header"
        )
        extra = _ROS1_ONLY.get(name, ())
        body: dict[str, Any] = {
            "__slots__": (*(n for n, _ in extra), *(n for n, _ in specs)),
            "_type": f"{package}/{self.class_name(name)}",
            "_has_header": header,
            "_slot_types": [*(t for _, t in extra), *(ros1_type_name(s) for _, s in specs)],
            "_md5sum": _Ros1Attribute("md5sum"),
            "_full_text": _Ros1Attribute("definition"),
        }
        bases: tuple[type, ...] = (GenpyMessage,)
        if name == TIME:
            bases = (TimeMixin, GenpyMessage)
        elif name == DURATION:
            bases = (DurationMixin, GenpyMessage)
        return bases, body

    def finish(self, cls: type[Message]) -> None:
        """The fields' defaults and ``__from_fields__``."""
        extra = _ROS1_ONLY.get(cls.__typename__, ())
        annotated = cls.__dict__.get("__field_defaults__", {})
        cls.__defaults__ = {  # type: ignore[attr-defined]
            **{n: _default_maker(t) for n, t in extra},
            **{n: _default_maker(s) for n, s in cls.__fields__},
            **{n: _constant(v) for n, v in annotated.items()},
        }
        if issubclass(cls, TVal):
            return  # Time(secs, nsecs): the decoders' positional call is its constructor
        g = SourceGen({"_new": object.__new__, "_cls": cls, "_MISSING": _MISSING})
        names = [n for n, _ in cls.__fields__]
        g.env.update({f"_d_{n}": d for n, d in cls.__defaults__.items()})  # type: ignore[attr-defined]
        # the ROS 1 only fields (a Header's seq) by keyword: the ROS 1 decoder gives them
        keywords = [f"{n}=0" for n, _ in extra]
        params = [f"{n}=_MISSING" for n in names] + (["*", *keywords] if keywords else [])
        g.emit(0, f"def __from_fields__({', '.join(params)}):")
        g.emit(1, "_o = _new(_cls)")
        for name, _ in extra:
            g.emit(1, f"_o.{name} = {name}")
        for name in names:
            g.emit(1, f"_o.{name} = _d_{name}() if {name} is _MISSING else {name}")
        g.emit(1, "return _o")
        _emit_init(g, [n for n, _ in extra] + names)
        exec("\n".join(g.lines), g.env)
        cls.__from_fields__ = staticmethod(g.env["__from_fields__"])  # type: ignore[attr-defined]
        setattr(cls, "__init__", g.env["__init__"])  # noqa: B010  # generated per class


def _emit_init(g: SourceGen, slots: list[str]) -> None:
    """genpy's constructor (:meth:`GenpyMessage.__init__`) for these slots, unrolled as genpy's
    generated classes have it: every field positionally, or any by keyword; None is the
    default."""
    g.env["_slots"] = frozenset(slots)
    g.env["_bad_keyword"] = _bad_keyword
    g.env["_bad_count"] = _bad_count
    g.emit(0, "def __init__(self, *args, **kwds):")
    g.emit(1, "if args:")
    g.emit(
        2, "if kwds: raise TypeError('Message constructor may only use args OR keywords, not both')"
    )
    g.emit(2, f"if len(args) != {len(slots)}: _bad_count(self, args)")
    if slots:
        g.emit(2, f"{', '.join(slots)}, = args")
    g.emit(1, "else:")
    g.emit(2, "if kwds and not _slots.issuperset(kwds): _bad_keyword(self, kwds)")
    for name in slots:
        g.emit(2, f"{name} = kwds.get('{name}')")
    for name in slots:
        g.emit(1, f"self.{name} = _d_{name}() if {name} is None else {name}")


def _bad_count(message: GenpyMessage, args: tuple[Any, ...]) -> None:
    raise TypeError(
        f"Invalid number of arguments, args should be {list(message.__slots__)} args are{args}"
    )


def _bad_keyword(message: GenpyMessage, kwds: dict[str, Any]) -> None:
    key = next(k for k in kwds if k not in message.__slots__)
    raise AttributeError(f"{key} is not an attribute of {type(message).__name__}")


def _typename(spec: Spec) -> str:
    return "" if isinstance(spec, (str, Seq, Array)) else spec.__typename__


def _constant(value: Any) -> Any:
    return lambda: value


def _default_maker(spec: Spec) -> Any:
    if isinstance(spec, str):
        value = default_for(spec.partition("<=")[0])
        return lambda: value
    return lambda: default_for(spec)


# Fields ROS 1's definition has before ROS 2's (genpy's slots; the ROS 1 codec numbers seq).
_ROS1_ONLY: dict[str, tuple[tuple[str, str], ...]] = {"std_msgs/msg/Header": (("seq", "uint32"),)}
_MISSING: Any = object()
FLAVOUR = GenpyFlavour()
