"""sensor_msgs/Image and CompressedImage as RGB uint8 arrays, as RViz's Image display shows them.

The encodings are those of RViz 2's ROSImageTexture::setFormatAndNormalizeDataIfNecessary
(rviz_default_plugins/displays/image/ros_image_texture.cpp): rgb8, rgba8, bgr8, bgra8 (and
8UC3/8UC4 as BGR/BGRA), mono8/8UC1, bayer_* shown as grey, mono16/16UC1/16SC1 and 32FC1
scaled to grey between a minimum and a maximum ("Normalize Range": the image's own range,
the median of the last "Median window" frames' ranges; else "Min Value".."Max Value"), and
yuv422/UYVY and YUYV with RViz's integer YUV formula. Unlike RViz, the row ``step`` and
``is_bigendian`` are honoured (RViz assumes packed little-endian rows).

CompressedImage (image_transport's compressed and compressedDepth) is decoded with Pillow,
already a dependency of the viewer extra. For the panel, :func:`image_pil` hands 8-bit RGB, BGR
and grey images to Pillow straight from the message's bytes (Pillow's own unpacking makes the
one copy and the channel order), so a camera image is not shuffled into an RGB array first.
"""

from __future__ import annotations

import collections
import io
import statistics
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer.displays.cloud import message_bytes
from robomodel.viewer.errors import ViewerError
from robomodel.viewer.limits import MAX_IMAGE_PIXELS

if TYPE_CHECKING:
    from PIL.Image import Image as PILImage

__all__ = [
    "ENCODINGS",
    "ImageError",
    "RangeNormalizer",
    "compressed_image_rgb",
    "image_pil",
    "image_rgb",
    "nearest_upscale",
    "scale_to_mono8",
    "upscale_factor",
    "upscaled_pil",
]

_COLOR = {"rgb8": (3, (0, 1, 2)), "rgba8": (4, (0, 1, 2)), "bgr8": (3, (2, 1, 0)),
          "bgra8": (4, (2, 1, 0)), "8UC3": (3, (2, 1, 0)), "8SC3": (3, (2, 1, 0)),
          "8UC4": (4, (2, 1, 0)), "8SC4": (4, (2, 1, 0))}  # fmt: skip
_MONO8 = ("mono8", "8UC1", "8SC1")
_SCALED = {"mono16": "u2", "16UC1": "u2", "16SC1": "i2", "32FC1": "f4"}
_YUV = {"yuv422": (1, 0, 3, 2), "uyvy": (1, 0, 3, 2), "UYVY": (1, 0, 3, 2),
        "yuv422_yuy2": (0, 1, 2, 3), "yuyv": (0, 1, 2, 3), "YUYV": (0, 1, 2, 3)}  # fmt: skip
ENCODINGS = (*_COLOR, *_MONO8, *_SCALED, *_YUV, "bayer_*")
# encodings Pillow unpacks as they are: encoding -> (Pillow mode, its raw mode, bytes a pixel)
_PIL_RAW = {"rgb8": ("RGB", "RGB", 3), "bgr8": ("RGB", "BGR", 3), "8UC3": ("RGB", "BGR", 3),
            "8SC3": ("RGB", "BGR", 3), **dict.fromkeys(_MONO8, ("L", "L", 1))}  # fmt: skip


class ImageError(ViewerError):
    """An image that cannot be shown (the display shows this as its status)."""


class RangeNormalizer:
    """RViz's "Normalize Range" with its "Median window": the median of the last frames'
    minima and maxima, so that the grey scale does not flicker with one frame's outlier."""

    def __init__(self, median_window: int = 5) -> None:
        self.median_window = median_window
        self._mins: collections.deque[float] = collections.deque()
        self._maxs: collections.deque[float] = collections.deque()

    def bounds(self, lo: float, hi: float) -> tuple[float, float]:
        """Add one frame's range; return the range to scale it with."""
        keep = max(int(self.median_window), 1)
        for buffer, value in ((self._mins, lo), (self._maxs, hi)):
            buffer.append(value)
            while len(buffer) > keep:
                buffer.popleft()
        if keep <= 1:
            return lo, hi
        return statistics.median_high(self._mins), statistics.median_high(self._maxs)


def upscale_factor(longest: int, *, min_side: int = 256, max_side: int = 2048) -> int:
    """How many times to repeat each pixel of an image whose longer side is ``longest`` so
    that it reaches ``min_side`` (never past ``max_side``); 1 for an image large enough."""
    return max(1, min(min_side // max(longest, 1), max_side // max(longest, 1)))


def nearest_upscale(image: NDArray[np.uint8], *, min_side: int = 256, max_side: int = 2048) -> NDArray[np.uint8]:  # fmt: skip
    """``image`` with each pixel repeated so that its longer side reaches ``min_side`` (never
    past ``max_side``): the browser filters textures linearly, RViz's map texture is sampled
    nearest (TFO_NONE), so cells must stay sharp squares."""
    longest = max(image.shape[0], image.shape[1])
    factor = upscale_factor(longest, min_side=min_side, max_side=max_side)
    if factor == 1:
        return image
    return np.repeat(np.repeat(image, factor, axis=0), factor, axis=1)


def scale_to_mono8(values: NDArray[Any], lo: float, hi: float) -> NDArray[np.uint8]:
    """``(v - lo) / (hi - lo)`` clipped to [0, 1], times 255, truncated (ROSImageTexture::
    convertTo8bit); black where ``hi <= lo`` or the value is not finite."""
    v = np.asarray(values, dtype=np.float64)
    if not hi > lo:
        return np.zeros(v.shape, dtype=np.uint8)
    scaled = np.clip((v - lo) / (hi - lo), 0.0, 1.0) * 255.0
    return np.nan_to_num(scaled, nan=0.0).astype(np.uint8)


def shown_rows(msg: Any) -> int:
    """The rows of ``msg`` the viewer draws: all of them, or the first ones within
    ``MAX_IMAGE_PIXELS`` (the rest is truncated).

    Raises:
        ImageError: one row alone is wider than the bound.
    """
    h, w = int(msg.height), int(msg.width)
    if w > MAX_IMAGE_PIXELS:
        raise ImageError(
            f"image of {w}x{h} pixels: a row is wider than the {MAX_IMAGE_PIXELS} pixels "
            "the viewer draws"
        )
    return min(h, MAX_IMAGE_PIXELS // max(w, 1))


def _rows(msg: Any, bytes_per_pixel: int) -> NDArray[np.uint8]:
    """The pixel bytes as (rows, width * bytes_per_pixel), honouring ``step``: the rows of
    :func:`shown_rows`."""
    w = int(msg.width)
    h = shown_rows(msg)
    row = w * bytes_per_pixel
    step = int(msg.step) or row
    data = message_bytes(msg.data)
    if step < row or len(data) < step * (h - 1) + row:
        raise ImageError(
            f"{msg.encoding} image of {w}x{h} needs {row} bytes a row; step is {step} and "
            f"data has {len(data)} bytes"
        )
    flat = np.frombuffer(data, dtype=np.uint8, count=min(len(data), step * h))
    if flat.size < step * h:  # the last row may end without its padding
        flat = np.concatenate([flat, np.zeros(step * h - flat.size, np.uint8)])
    return flat.reshape(h, step)[:, :row]


def _yuv(msg: Any, order: tuple[int, int, int, int]) -> NDArray[np.uint8]:
    rows = _rows(msg, 2)
    quads = rows.reshape(rows.shape[0], -1, 4).astype(np.int32)
    y0, u, y1, v = (quads[..., k] for k in order)
    out = np.empty((rows.shape[0], quads.shape[1], 2, 3), dtype=np.uint8)
    u, v = u - 128, v - 128
    for k, y in enumerate((y0, y1)):  # RViz's pixelYUVToRGB, in integer arithmetic
        r = y + _div(1403 * v, 1000)
        g = y + _div(344 * u - 714 * v, 1000)
        b = y + _div(1770 * u, 1000)
        out[:, :, k] = np.clip(np.stack([r, g, b], axis=-1), 0, 255)
    return out.reshape(rows.shape[0], -1, 3)[:, : int(msg.width)]


def _div(a: NDArray[np.int32], b: int) -> NDArray[np.int32]:
    """C++'s integer division (towards zero), not numpy's floor division."""
    out: NDArray[np.int32] = np.sign(a) * (np.abs(a) // b)
    return out


def image_rgb(
    msg: Any,
    *,
    normalize: bool = True,
    min_value: float = 0.0,
    max_value: float = 1.0,
    normalizer: RangeNormalizer | None = None,
) -> NDArray[np.uint8]:
    """The image as (height, width, 3) RGB uint8 (alpha dropped).

    Args:
        msg: A sensor_msgs/Image.
        normalize: RViz's "Normalize Range" for 16-bit and float images.
        min_value, max_value: "Min Value", "Max Value" when not normalising.
        normalizer: Keeps the "Median window" across frames; one frame's range if None.

    Raises:
        ImageError: Unknown encoding, or data too short for width, height and step.
    """
    enc = str(msg.encoding)
    h, w = shown_rows(msg), int(msg.width)
    if enc in _COLOR:
        channels, order = _COLOR[enc]
        pixels = _rows(msg, channels).reshape(h, w, channels)
        # channel by channel: numpy copies an index list or a reversed channel axis 20-50x
        # slower (10-20 ms for 640x480)
        rgb = np.empty((h, w, 3), dtype=np.uint8)
        for k, source in enumerate(order):
            rgb[..., k] = pixels[..., source]
        return rgb
    if enc in _MONO8 or enc.startswith("bayer"):
        grey = _rows(msg, 1)
    elif enc in _SCALED:
        kind = _SCALED[enc]
        byte_order = ">" if msg.is_bigendian else "<"
        values = _rows(msg, int(kind[1])).copy().view(byte_order + kind).reshape(h, w)
        grey = _scaled(values, normalize, min_value, max_value, normalizer)
    elif enc in _YUV:
        return _yuv(msg, _YUV[enc])
    else:
        raise ImageError(
            f"Unsupported image encoding [{enc}]; supported are: {', '.join(ENCODINGS)}"
        )
    return np.repeat(grey[:, :, None], 3, axis=2)


def image_pil(
    msg: Any,
    *,
    normalize: bool = True,
    min_value: float = 0.0,
    max_value: float = 1.0,
    normalizer: RangeNormalizer | None = None,
    min_side: int = 1,
) -> PILImage:
    """The image as a Pillow image (mode RGB, or L for grey encodings), the same pixels as
    :func:`image_rgb`, upscaled (each pixel repeated) until its longer side reaches ``min_side``.

    rgb8, bgr8 (8UC3), mono8 (8UC1) and bayer_* are unpacked by Pillow from the message's bytes
    in one pass; the other encodings go through :func:`image_rgb`. Arguments and errors are
    :func:`image_rgb`'s.
    """
    from PIL import Image

    enc = str(msg.encoding)
    raw = _PIL_RAW.get(enc) or (("L", "L", 1) if enc.startswith("bayer") else None)
    if raw is None:
        rgb = image_rgb(msg, normalize=normalize, min_value=min_value, max_value=max_value,
                        normalizer=normalizer)  # fmt: skip
        image = Image.fromarray(rgb)
    else:
        mode, raw_mode, channels = raw
        rows = np.ascontiguousarray(_rows(msg, channels))  # padded rows: one copy of the rest
        image = Image.frombuffer(mode, (int(msg.width), rows.shape[0]), rows, "raw", raw_mode, 0, 1)  # fmt: skip
    return upscaled_pil(image, min_side=min_side)


def upscaled_pil(image: PILImage, *, min_side: int) -> PILImage:
    """``image`` with each pixel repeated so that its longer side reaches ``min_side`` (see
    :func:`nearest_upscale`)."""
    from PIL import Image

    factor = upscale_factor(max(image.size), min_side=min_side)
    if factor == 1:
        return image
    return image.resize((image.width * factor, image.height * factor), Image.Resampling.NEAREST)


def _scaled(values: NDArray[Any], normalize: bool, lo: float, hi: float, normalizer: RangeNormalizer | None) -> NDArray[np.uint8]:  # fmt: skip
    if normalize:
        finite = values[np.isfinite(values)] if values.dtype.kind == "f" else values
        lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 0.0)
        if normalizer is not None:
            lo, hi = normalizer.bounds(lo, hi)
    return scale_to_mono8(values, lo, hi)


def compressed_image_rgb(
    msg: Any,
    *,
    normalize: bool = True,
    min_value: float = 0.0,
    max_value: float = 1.0,
    normalizer: RangeNormalizer | None = None,
) -> NDArray[np.uint8]:
    """A sensor_msgs/CompressedImage (jpeg, png; compressedDepth png) as RGB uint8.

    ``format`` is image_transport's ("jpeg", "png", "bgr8; jpeg compressed bgr8",
    "16UC1; compressedDepth png"): a compressedDepth payload starts with a 12-byte
    ConfigHeader (compressed_depth_image_transport) before its PNG, which holds 16-bit depths
    scaled to grey as a 16UC1 image is.
    """
    from PIL import Image, UnidentifiedImageError

    fmt = str(msg.format)
    data = message_bytes(msg.data)
    depth = "compresseddepth" in fmt.lower()
    try:
        with Image.open(io.BytesIO(data[12:] if depth else data)) as img:
            if img.width * img.height > MAX_IMAGE_PIXELS:  # read from the header: not decoded
                raise ImageError(
                    f"compressed image of {img.width}x{img.height} pixels is larger than the "
                    f"{MAX_IMAGE_PIXELS} pixels the viewer draws; not drawn"
                )
            img.load()
            if img.mode in ("I;16", "I;16B", "I", "F"):
                values = np.asarray(img)
                grey = _scaled(values, normalize, min_value, max_value, normalizer)
                return np.repeat(grey[:, :, None], 3, axis=2)
            return np.asarray(img.convert("RGB"), dtype=np.uint8)
    except (UnidentifiedImageError, OSError, ValueError) as exc:
        raise ImageError(f"cannot decode compressed image (format '{fmt}'): {exc}") from None
