"""robomodel's message and service classes written out as ``.msg`` / ``.srv`` files, for the
zenoh-ros2-sdk process of the wire tests: the SDK reads definitions from files and computes
every type hash itself, independently of robomodel's ``typehash``."""

from __future__ import annotations

from pathlib import Path

from robomodel.runtime.msg._schema import Array, Message, Seq, Service, Spec

__all__ = ["write_definitions"]


def _type_text(spec: Spec) -> str:
    if isinstance(spec, str):
        return spec
    if isinstance(spec, Seq):
        bound = f"<={spec.bound}" if spec.bound is not None else ""
        return f"{_type_text(spec.item)}[{bound}]"
    if isinstance(spec, Array):
        return f"{_type_text(spec.item)}[{spec.size}]"
    package, _, name = spec.__typename__.split("/")
    return f"{package}/{name}"


def _text(cls: type[Message]) -> str:
    return "".join(f"{_type_text(spec)} {name}\n" for name, spec in cls.__fields__)


def _nested(cls: type[Message], out: set[type[Message]]) -> None:
    for _, spec in cls.__fields__:
        item = spec.item if isinstance(spec, Seq | Array) else spec
        if isinstance(item, type) and issubclass(item, Message) and item not in out:
            out.add(item)
            _nested(item, out)


def write_definitions(root: Path, types: list[type[Message] | type[Service]]) -> Path:
    """Write ``types`` and every message they use under ``root/<pkg>/{msg,srv}/``."""
    messages: set[type[Message]] = set()
    for kind in types:
        if isinstance(kind, type) and issubclass(kind, Service):
            package, _, name = kind.__typename__.split("/")
            path = root / package / "srv" / f"{name}.srv"
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(_text(kind.Request) + "---\n" + _text(kind.Response))
            for half in (kind.Request, kind.Response):
                _nested(half, messages)
        else:
            messages.add(kind)
            _nested(kind, messages)
    for cls in messages:
        package, _, name = cls.__typename__.split("/")
        path = root / package / "msg" / f"{name}.msg"
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(_text(cls))
    return root
