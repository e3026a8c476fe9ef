"""Placing the robots' links for one scene update, and what the placement found.

Each robot is looked up in the fixed frame unless its RobotModel display's Update Interval holds
it back (then it stays where it was, and what the last placement found about it stays too).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from robomodel.viewer.displays.tf import TFDisplay
from robomodel.viewer.layout import beside_root_pose
from robomodel.viewer.link_poses import LinkPoses

__all__ = ["FramePoses", "Placement"]


@dataclass
class FramePoses:
    """The placed links' frames and their poses in the fixed frame, robot by robot."""

    frames: list[str] = field(default_factory=list)
    wxyzs: list[np.ndarray] = field(default_factory=list)
    xyzs: list[np.ndarray] = field(default_factory=list)
    shown: list[np.ndarray] = field(default_factory=list)

    def show_in(self, displays: Sequence[Any], buffer: Any) -> None:
        """Every frame's pose in the fixed frame to the TF displays among ``displays``."""
        tf_displays = [d for d in displays if isinstance(d, TFDisplay)]
        if not tf_displays or not self.frames:
            return
        frames = tuple(self.frames)
        wxyz, xyz = np.concatenate(self.wxyzs), np.concatenate(self.xyzs)
        visible = np.concatenate(self.shown)
        for display in tf_displays:
            display.show_frames(frames, wxyz, xyz, visible, buffer)


@dataclass
class Placement:
    """What the placements found, per robot number: its extent [m] once all of it was placed,
    its frames without a transform, whether it was drawn beside the fixed frame's tree; and
    when a robot held back by its Update Interval is due [monotonic s]."""

    extent_m: dict[int, float] = field(default_factory=dict)
    missing: dict[int, tuple[str, ...]] = field(default_factory=dict)
    beside: set[int] = field(default_factory=set)
    due_s: float = float("inf")

    def forget(self, number: int) -> None:
        """Robot ``number`` is gone."""
        self.extent_m.pop(number, None)
        self.missing.pop(number, None)
        self.beside.discard(number)

    def place(
        self, sessions: Sequence[Any], buffer: Any, fixed_frame: str, now_s: float
    ) -> FramePoses:
        """Place every robot that is due (inside the caller's atomic scene update)."""
        missing, beside = self.missing, self.beside
        self.missing, self.beside, self.due_s = {}, set(), float("inf")
        placed = FramePoses()
        for session in sessions:
            updates = session.link_updates
            number = session.number
            if not updates.due(now_s, fixed_frame):
                # within its RobotModel's Update Interval: left where it is until then
                self.due_s = min(self.due_s, updates.next_s())
                if number in missing:
                    self.missing[number] = missing[number]
                if number in beside:
                    self.beside.add(number)
                continue
            root = beside_root_pose(session, sessions, fixed_frame, self.extent_m)
            poses = session.link_poses(buffer, fixed_frame, root)
            if poses is None or session.display is None:
                continue
            session.display.set_poses(poses.wxyz, poses.xyz, poses.visible)
            updates.placed(now_s, fixed_frame)
            self._note(number, poses)
            placed.frames.extend(session.link_frames())
            placed.wxyzs.append(poses.wxyz)
            placed.xyzs.append(poses.xyz)
            placed.shown.append(poses.visible)
        return placed

    def _note(self, number: int, poses: LinkPoses) -> None:
        if number not in self.extent_m and poses.visible.all():
            self.extent_m[number] = float(
                np.linalg.norm(poses.xyz - poses.xyz[0], axis=1).max(initial=0.0)
            )
        self.missing[number] = poses.missing
        if not poses.connected:
            self.beside.add(number)
