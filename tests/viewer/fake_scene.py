"""A stand-in for viser's scene API that records what displays add (tests without a browser)."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np

from robomodel.viewer.displays import DisplayContext, Placement


class FakeNode:
    def __init__(self, scene: FakeScene, name: str, kind: str, kwargs: dict[str, Any]) -> None:
        self.scene, self.name, self.kind, self.kwargs = scene, name, kind, kwargs
        self.visible = bool(kwargs.get("visible", True))
        self.position = kwargs.get("position", (0.0, 0.0, 0.0))
        self.wxyz = kwargs.get("wxyz", (1.0, 0.0, 0.0, 0.0))

    def __setattr__(self, name: str, value: Any) -> None:
        # a prop set on the handle (viser sends it as an update) is kept with the others
        object.__setattr__(self, name, value)
        if name not in ("scene", "name", "kind", "kwargs") and "kwargs" in self.__dict__:
            self.kwargs[name] = value

    def remove(self) -> None:
        self.scene.nodes.pop(self.name, None)


class FakeScene:
    """``add_<kind>(name, **kwargs)`` for any kind; ``nodes`` by name."""

    def __init__(self) -> None:
        self.nodes: dict[str, FakeNode] = {}

    def __getattr__(self, attr: str) -> Callable[..., FakeNode]:
        if not attr.startswith("add_"):
            raise AttributeError(attr)

        def add(name: str, *args: Any, **kwargs: Any) -> FakeNode:
            node = FakeNode(self, name, attr[4:], {**kwargs, "args": args} if args else kwargs)
            self.nodes[name] = node
            return node

        return add

    def visible(self, prefix: str = "") -> dict[str, FakeNode]:
        return {n: v for n, v in self.nodes.items() if v.visible and n.startswith(prefix)}


class FakeClock:
    def __init__(self) -> None:
        self.ns = time.time_ns()

    def __call__(self) -> int:
        return self.ns


def fake_context(
    scene: FakeScene, *, fixed: str = "map", clock: Callable[[], int] | None = None
) -> DisplayContext:
    return DisplayContext(
        scene=scene,
        gui=None,
        fixed_frame=lambda: fixed,
        topic_types=lambda _topic: frozenset(),
        post=lambda work: work(),
        now_ns=clock or time.time_ns,
    )


def lookup_from(frames: dict[str, np.ndarray]) -> Callable[[str, int], Placement]:
    """A FrameLookup knowing ``frames`` (name -> 4x4 in the fixed frame 'map')."""

    def lookup(frame: str, _stamp_ns: int = 0) -> Placement:
        if frame in frames:
            return Placement(frames[frame])
        return Placement(None, f"No transform from [{frame}] to [map]")

    return lookup
