"""Pacing scene updates to what the pages can take."""

from __future__ import annotations

from typing import Any

__all__ = ["page_behind"]


def page_behind(
    buffer: Any, last_push_ids: tuple[int, int] | None, last_push_s: float, now: float
) -> bool:
    """Whether a page has not yet been sent all of the previous update, when that update
    takes more than one websocket frame (``buffer``: viser's broadcast buffer, or None).

    A new update replaces the pose messages still waiting, so when the pages cannot take
    updates as fast as they are made (a 1,000-link robot: thousands of messages, tens of
    frames each), the links queued last would never be sent. Waiting for viser's send
    cursor keeps such updates whole; an update that fits in one frame is sent whole anyway
    and is not waited for (the next one is computed while it goes). At most 0.5 s, so that
    a stalled page does not freeze the others.
    """
    if buffer is None or last_push_ids is None or now - last_push_s > 0.5:
        return False
    first, last = last_push_ids
    if last - first + 1 <= getattr(buffer, "max_window_size", 128):
        return False
    cursors = list(buffer.generator_cursors.values())
    return bool(cursors) and min(cursors) < last
