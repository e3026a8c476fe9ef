"""The action types behind a user's action class, and messages moved between flavours."""

from __future__ import annotations

from typing import Any

__all__ = ["as_class", "robomodel_action", "uuid_key"]


def robomodel_action(action_type: Any) -> Any:
    """robomodel's own action class of ``action_type``'s type (what its server builds with)."""
    from robomodel.runtime.msg._resolver import resolve_action

    name = action_type.__typename__
    return resolve_action(name, name)


def as_class(msg: Any, cls: Any) -> Any:
    """``msg`` as an instance of ``cls`` (the same type, maybe another flavour's class): the
    message itself when it is one, else its CDR decoded into ``cls``."""
    if type(msg) is cls:
        return msg
    from robomodel.runtime.msg.cdr import deserialize, serialize

    return deserialize(serialize(msg), cls)


def uuid_key(uuid_msg: Any) -> bytes:
    """A goal id (unique_identifier_msgs/UUID of any flavour) as 16 bytes."""
    return bytes(bytearray(uuid_msg.uuid))
