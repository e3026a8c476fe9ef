"""A ROS 1 launch on the ROS 1 wire: find the master at ``ROS_MASTER_URI`` or start one, as
roslaunch starts a roscore when none answers.

The launch's parameters then live in that master's parameter server (``rosparam get`` reads
them), set as ``/roslaunch``; the hosted master also gets roscore's ``/run_id``,
``/rosdistro`` and ``/rosversion``, and roscore's ``/rosout`` node (``/rosout_agg``), run by
the launch's loop.
"""

from __future__ import annotations

import uuid
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from robomodel.launch.ros1.params import Binary

__all__ = ["Ros1Bus", "open_ros1", "plain_value"]

ROSDISTRO = "noetic"  # the distribution whose message definitions robomodel speaks
ROSVERSION = "1.16.0"


def plain_value(value: Any) -> Any:
    """A launch value as XML-RPC carries it (a ``binfile`` as bytes)."""
    if isinstance(value, Binary):
        return value.data
    if isinstance(value, Mapping):
        return {str(k): plain_value(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [plain_value(v) for v in value]
    return value


class _Params:
    """The master's parameters, taking launch values (``Binary``) as they are."""

    def __init__(self, uri: str) -> None:
        from robomodel.runtime.transport.ros1.param_client import MasterParams

        self._params = MasterParams(uri)
        self.get = self._params.get
        self.has = self._params.has
        self.delete = self._params.delete
        self.names = self._params.names
        self.search = self._params.search

    def set(self, name: str, value: Any) -> None:
        self._params.set(name, plain_value(value))


@dataclass
class Ros1Bus:
    context: Any
    params: Any
    master: Any  # the hosted Master, or None when another process runs it
    uri: str
    rosout: Any = None  # roscore's rosout node, beside a hosted master

    def close(self) -> None:
        if self.rosout is not None:
            self.rosout.close()
        if self.master is not None:
            self.master.close()


def open_ros1(uri: str | None, log: Callable[[str], None]) -> Ros1Bus:
    from robomodel.runtime import Context
    from robomodel.runtime.transport.ros1.master import Master, master_answers
    from robomodel.runtime.transport.ros1.names import master_bind_host, master_uri

    uri = master_uri(uri)
    master = None
    if master_answers(uri):
        log(f"[launch] ROS 1 master at {uri}")
    else:
        master = Master(uri, master_bind_host(uri))
        log(f"[launch] no ROS 1 master answered at {uri}: started one (as roscore)")
    try:
        params = _Params(uri)
        if master is not None:
            params.set("/run_id", str(uuid.uuid1()))
            params.set("/rosdistro", ROSDISTRO + "\n")
            params.set("/rosversion", ROSVERSION + "\n")
        context = Context("ros1", master=uri)
        rosout = None
        if master is not None:
            from robomodel.runtime.nodes.rosout import RosoutAggregator

            rosout = RosoutAggregator(context)
    except Exception:
        if master is not None:
            master.close()
        raise
    return Ros1Bus(context, params, master, uri, rosout)
