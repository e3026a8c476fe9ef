"""The parameter server of a ROS 1 master, through its XML-RPC API, with the interface of
:class:`~robomodel.runtime.transport.ros1.param_tree.ParamTree` (get, set, has, delete, names,
search), so that a launch and the CLI use a real roscore and robomodel's own master alike."""

from __future__ import annotations

from typing import Any

from robomodel.runtime.transport.ros1.param_tree import ParamServerError
from robomodel.runtime.transport.ros1.xmlrpc_io import Ros1WireError, call

__all__ = ["MasterParams"]


class MasterParams:
    """Parameters of the master at ``uri``, called as ``caller_id`` (names resolve from it)."""

    def __init__(self, uri: str, caller_id: str = "/roslaunch", timeout_s: float = 5.0) -> None:
        self.uri = uri
        self.caller_id = caller_id
        self._timeout_s = timeout_s

    def _call(self, method: str, *args: Any) -> Any:
        try:
            return call(self.uri, method, self.caller_id, *args, timeout_s=self._timeout_s)
        except Ros1WireError as exc:
            raise ParamServerError(str(exc)) from None

    def get(self, name: str) -> Any:
        return self._call("getParam", name)

    def set(self, name: str, value: Any) -> None:
        self._call("setParam", name, value)

    def has(self, name: str) -> bool:
        return bool(self._call("hasParam", name))

    def delete(self, name: str) -> None:
        self._call("deleteParam", name)

    def names(self) -> list[str]:
        return sorted(str(n) for n in self._call("getParamNames"))

    def search(self, namespace: str, key: str) -> str | None:
        """searchParam from ``namespace`` (a node's name, as rosmaster searches from the
        caller's id)."""
        try:
            found = call(self.uri, "searchParam", namespace, key, timeout_s=self._timeout_s)
        except Ros1WireError:
            return None
        return str(found) if found else None
