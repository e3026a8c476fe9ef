"""lifecycle_msgs (Jazzy): State, the state of a managed node or hardware component."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from robomodel.runtime.msg._schema import Message

__all__ = [
    "State",
]


@dataclass(slots=True)
class State(Message):
    PRIMARY_STATE_UNKNOWN: ClassVar[int] = 0
    PRIMARY_STATE_UNCONFIGURED: ClassVar[int] = 1
    PRIMARY_STATE_INACTIVE: ClassVar[int] = 2
    PRIMARY_STATE_ACTIVE: ClassVar[int] = 3
    PRIMARY_STATE_FINALIZED: ClassVar[int] = 4
    TRANSITION_STATE_CONFIGURING: ClassVar[int] = 10
    TRANSITION_STATE_CLEANINGUP: ClassVar[int] = 11
    TRANSITION_STATE_SHUTTINGDOWN: ClassVar[int] = 12
    TRANSITION_STATE_ACTIVATING: ClassVar[int] = 13
    TRANSITION_STATE_DEACTIVATING: ClassVar[int] = 14
    TRANSITION_STATE_ERRORPROCESSING: ClassVar[int] = 15

    id: int = 0
    label: str = ""
    __typename__ = "lifecycle_msgs/msg/State"
    __fields__ = (("id", "uint8"), ("label", "string"))
