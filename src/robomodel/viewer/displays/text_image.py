"""A TEXT_VIEW_FACING marker's text as an RGBA image, in the marker's colour.

viser's labels are black on white and cannot take a colour, so the viewer draws RViz's
view-facing text as an image node turned to the page's camera. RViz's MovableText
(rviz_rendering ``movable_text.cpp``) draws each line ``character height`` = ``scale.z`` high,
the lines centred, in the marker's colour and alpha, with no background: here the image is
the text in that colour, its alpha the glyph coverage times the marker's alpha, and a line of
the image (the font's ascent plus descent) is ``scale.z`` in the scene.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["TextImage", "text_image"]

_FONT_PX = 48  # rasterised line height [px]: sharp at the sizes a page shows markers


@dataclass(frozen=True, slots=True)
class TextImage:
    """The text's pixels and their size in the scene.

    Attributes:
        rgba: Shape (height, width, 4), uint8, read-only.
        width_m, height_m: The image's size in the scene [m].
    """

    rgba: NDArray[np.uint8]
    width_m: float
    height_m: float


@functools.cache
def _font() -> object:
    from PIL import ImageFont

    return ImageFont.load_default(size=_FONT_PX)  # Pillow's own FreeType font (no system font)


def text_image(text: str, rgb: tuple[int, int, int], alpha: float, height_m: float) -> TextImage:
    """``text`` in colour ``rgb`` (0..255) and ``alpha`` (0..1), lines ``height_m`` high [m]."""
    from PIL import Image, ImageDraw

    font = _font()
    ascent, descent = font.getmetrics()  # type: ignore[attr-defined]
    line_px = ascent + descent
    lines = text.split("\n") or [""]
    widths = [max(1, round(font.getlength(line))) for line in lines]  # type: ignore[attr-defined]
    pad = 2  # antialiased edges must not be cut
    width_px, height_px = max(widths) + 2 * pad, line_px * len(lines) + 2 * pad
    coverage = Image.new("L", (width_px, height_px), 0)
    draw = ImageDraw.Draw(coverage)
    for row, (line, line_width) in enumerate(zip(lines, widths, strict=True)):
        draw.text(((width_px - line_width) / 2, pad + row * line_px), line, fill=255, font=font)  # type: ignore[arg-type]
    a = np.asarray(coverage, dtype=np.float32) * min(1.0, max(0.0, alpha))
    rgba = np.empty((height_px, width_px, 4), np.uint8)
    rgba[..., :3] = rgb
    rgba[..., 3] = np.round(a).astype(np.uint8)
    rgba.setflags(write=False)
    metres_per_px = height_m / line_px
    return TextImage(rgba, width_px * metres_per_px, height_px * metres_per_px)
