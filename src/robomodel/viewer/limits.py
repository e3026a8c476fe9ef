"""How much of a message the viewer draws, and keeps: text, points, pixels, markers,
parameters, Odometry messages waiting for a draw.

Whatever a peer publishes is drawn within these bounds; what is over one is drawn truncated
(the first part of it) and the display's status says so, so a 10,000-character text marker, a
marker of 10^7 points or a flood of markers costs a bounded time and memory. Each default is
documented in ``docs/reference/limits.md``.
"""

from __future__ import annotations

__all__ = [
    "MAX_CLOUDS_KEPT",
    "MAX_CLOUD_BYTES_KEPT",
    "MAX_CLOUD_POINTS",
    "MAX_IMAGE_PIXELS",
    "MAX_MARKERS",
    "MAX_MARKERS_PER_NAMESPACE",
    "MAX_MARKER_POINTS",
    "MAX_ODOMETRY_PENDING",
    "MAX_PARAMETERS_SHOWN",
    "MAX_TEXT_CHARS",
    "MAX_TEXT_LINES",
    "truncated_text",
]

MAX_TEXT_CHARS = 1_000  # a TEXT_VIEW_FACING marker's text: at most ~3 Mpx (12 MB) rasterised
MAX_TEXT_LINES = 100
MAX_MARKER_POINTS = 1_000_000  # points (and colors) of one marker
MAX_MARKERS_PER_NAMESPACE = 10_000
MAX_MARKERS = 100_000  # of one Marker or MarkerArray display
MAX_CLOUD_POINTS = 2_000_000  # of one PointCloud2 (a 64-beam lidar sends ~130,000)
# PointCloud2 clouds kept for its Decay Time (the oldest dropped first): 10 s of a 100 Hz
# sensor, and the point data of ~10 s of a 64-beam lidar at 10 Hz (~2 MB a cloud)
MAX_CLOUDS_KEPT = 1_000
MAX_CLOUD_BYTES_KEPT = 256 * 2**20
MAX_IMAGE_PIXELS = 4096 * 4096  # of one Image, CompressedImage or Camera frame
MAX_PARAMETERS_SHOWN = 1_000  # controls the Parameters tool builds for one node
# Odometry messages kept between two draws (0.1 s apart): 10 kHz of odometry; the newest are kept
MAX_ODOMETRY_PENDING = 1_000


def truncated_text(text: str) -> tuple[str, str]:
    """``text`` within ``MAX_TEXT_CHARS`` and ``MAX_TEXT_LINES`` (cut with ``…``), and a note
    saying what was cut ("" when nothing was)."""
    lines = text.split("\n")
    if len(text) <= MAX_TEXT_CHARS and len(lines) <= MAX_TEXT_LINES:
        return text, ""
    shown = "\n".join(lines[:MAX_TEXT_LINES])[:MAX_TEXT_CHARS] + "…"
    return shown, (
        f"text of {len(text)} characters in {len(lines)} lines drawn truncated to "
        f"{MAX_TEXT_CHARS} characters and {MAX_TEXT_LINES} lines"
    )
