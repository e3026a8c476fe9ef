"""The status panel's text: load errors, missing meshes, frames without transforms."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from robomodel.viewer.scene import GeometryProblem
from robomodel.viewer.session import LoadFailure

__all__ = ["RobotStatus", "render_status"]

_MAX_LISTED = 8


@dataclass(frozen=True, slots=True)
class RobotStatus:
    """What the status panel says about one robot."""

    label: str
    path: str
    failure: LoadFailure | None
    problems: tuple[GeometryProblem, ...]
    missing_frames: tuple[str, ...]
    fixed_frame: str
    placed_beside: bool
    pending_meshes: int


def _code(lines: Sequence[str]) -> str:
    body = "\n".join(line.replace("```", "'''") for line in lines)
    return f"```\n{body}\n```"


def render_status(robots: Sequence[RobotStatus], fixed_frame_known: bool, fixed: str) -> str:
    """Markdown for the status panel ("OK" when there is nothing to report)."""
    parts: list[str] = []
    if not fixed_frame_known:
        parts.append(f"**Fixed Frame** `{fixed}` does not exist (yet).")
    for robot in robots:
        head = f"**{robot.label}** (`{robot.path}`)"
        if robot.failure is not None:
            parts.append(
                f"{head}: **error**, showing the last good model\n\n"
                + _code([robot.failure.message, *robot.failure.notes])
            )
        if robot.problems:
            lines = [p.format() for p in robot.problems]
            parts.append(f"{head}: {len(lines)} mesh(es) not drawn:\n\n" + _code(lines))
        if robot.pending_meshes:
            parts.append(f"{head}: loading {robot.pending_meshes} mesh(es)...")
        if robot.missing_frames:
            shown = robot.missing_frames[:_MAX_LISTED]
            more = len(robot.missing_frames) - len(shown)
            lines = [f"No transform from [{f}] to [{robot.fixed_frame}]" for f in shown]
            if more > 0:
                lines.append(f"... and {more} more")
            parts.append(f"{head}:\n\n" + _code(lines))
        if robot.placed_beside:
            parts.append(
                f"{head}: its tree is not connected to the Fixed Frame `{robot.fixed_frame}`; "
                "drawn beside it"
            )
    return "\n\n".join(parts) if parts else "OK"
