"""The status panel's text: load errors, missing meshes, frames without transforms."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence, Set
from dataclasses import dataclass
from typing import Any

from robomodel.viewer.markup import Markup, code, escape_markdown, md
from robomodel.viewer.scene import GeometryProblem
from robomodel.viewer.session import LoadFailure, RobotSession

__all__ = ["RobotStatus", "render_status", "viewer_status"]

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
    substituted: tuple[tuple[str, str], ...] = ()  # (missing package, link)
    topic: str = ""  # the description topic of a robot without a file


def _short(path: str | None, base_dir: str) -> str:
    if path is None:
        return "<string>"
    relative = os.path.relpath(path, base_dir)
    return path if relative.startswith("..") else relative


def _failure(failure: LoadFailure, base_dir: str) -> Markup:
    if not failure.diagnostics:
        return escape_markdown(failure.message)
    lines = []
    for diagnostic in failure.diagnostics:
        loc = diagnostic.location
        where = ":".join(
            [_short(loc.path, base_dir)] + [str(v) for v in (loc.line, loc.column) if v is not None]
        )
        lines.append(md("{}: {}: {}", code(where), diagnostic.severity.value, diagnostic.message))
    return Markup("\n\n".join(lines))


def _substitution_lines(head: Markup, substituted: Sequence[tuple[str, str]]) -> list[Markup]:
    """One line per missing package whose visual meshes were drawn as collision shapes."""
    links: dict[str, set[str]] = {}
    for package, link in substituted:
        links.setdefault(package, set()).add(link)
    lines = []
    for package, names in links.items():
        hint = " (if it is one of example-robot-data's robots: `pip install example-robot-data`)"
        lines.append(
            md(
                "{}: package {} not found: {} link(s) drawn with their collision shapes instead "
                "of their visual meshes" + (hint if package.endswith("_description") else ""),
                head,
                code(package),
                len(names),
            )
        )
    return lines


def render_status(robots: Sequence[RobotStatus], fixed_frame_known: bool, fixed: str) -> Markup:
    """Markdown for the status panel ("OK" when there is nothing to report)."""
    parts: list[Markup] = []
    if not fixed_frame_known:
        parts.append(md("**Fixed Frame** {} does not exist (yet).", code(fixed)))
    for robot in robots:
        base_dir = os.path.dirname(os.path.abspath(robot.path))
        head = md("**{}** ({})", robot.label, code(os.path.basename(robot.path) or robot.topic))
        if robot.failure is not None:
            parts.append(
                md(
                    "{}: **error**, showing the last good model:\n\n{}",
                    head,
                    _failure(robot.failure, base_dir),
                )
            )
        if robot.problems:
            lines = [
                md("- {} ({}): {}: {}", p.link, p.kind, code(p.uri), p.reason)
                for p in robot.problems
            ]
            parts.append(
                md("{}: {} mesh(es) not drawn:\n\n{}", head, len(lines), Markup("\n".join(lines)))
            )
        parts.extend(_substitution_lines(head, robot.substituted))
        if robot.pending_meshes:
            parts.append(md("{}: loading {} mesh(es)...", head, robot.pending_meshes))
        if robot.missing_frames:
            shown = robot.missing_frames[:_MAX_LISTED]
            more = len(robot.missing_frames) - len(shown)
            lines = [
                md("- No transform from {} to {}", f"[{f}]", f"[{robot.fixed_frame}]")
                for f in shown
            ]
            if more > 0:
                lines.append(md("- ... and {} more", more))
            parts.append(md("{}:\n\n{}", head, Markup("\n".join(lines))))
        if robot.placed_beside:
            parts.append(
                md(
                    "{}: its tree is not connected to the Fixed Frame {}; drawn beside it",
                    head,
                    code(robot.fixed_frame),
                )
            )
    return Markup("\n\n".join(parts)) if parts else md("OK")


def viewer_status(
    sessions: Sequence[RobotSession],
    buffer: Any,
    fixed_frame: str,
    missing: Mapping[int, tuple[str, ...]],
    beside: Set[int],
) -> Markup:
    """The status panel's Markdown for the viewer's robots (see :func:`render_status`).

    Args:
        sessions: The robots.
        buffer: The viewer's TF buffer (whether the Fixed Frame exists).
        fixed_frame: The viewer's Fixed Frame.
        missing: Robot number -> its links without a transform at the last update.
        beside: Numbers of the robots drawn beside the Fixed Frame's tree.
    """
    statuses = []
    for session in sessions:
        display = session.display
        statuses.append(
            RobotStatus(
                label=session.label,
                path=session.source.path,
                failure=session.failure,
                problems=tuple(display.problems) if display is not None else (),
                missing_frames=missing.get(session.number, ()),
                fixed_frame=fixed_frame,
                placed_beside=session.number in beside and len(sessions) > 1,
                pending_meshes=display.pending_meshes if display is not None else 0,
                substituted=tuple(display.substituted) if display is not None else (),
                topic=session.source.topic or "",
            )
        )
    known = fixed_frame in buffer.frames or any(fixed_frame == s.root_frame for s in sessions)
    return render_status(statuses, known, fixed_frame)
