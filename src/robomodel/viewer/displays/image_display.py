"""RViz's Image display: the latest sensor_msgs/Image (or CompressedImage) in a panel of its own.

RViz 2's Image display (image_display.cpp) shows the image in its own panel, docked beside the
3D view as soon as the display is added, with "Normalize Range", "Min Value", "Max Value" and
"Median window" for 16-bit and float images; a topic of type CompressedImage
(image_transport's ``.../compressed``) is decoded as RViz's compressed transport would. Here
the panel is an image area at the top of the page's control panel, expanded, named after the
display, hidden while the display is disabled (its options stay in the Displays tree).

RViz shows the newest image at each render, at its Frame Rate (Global Options, 30 by
default): an image is converted when it arrives if the Frame Rate allows one more (a budget of
one image per frame, of which up to :data:`BURST_FRAMES` may be saved, so that images arriving
bunched by the network's jitter are all shown while the rate over any second stays the Frame
Rate); else it waits, and the next arrival or the next draw (10 Hz) shows the newest. Older
ones are skipped (counted in ``skipped``). A converted image goes to a
:class:`~robomodel.viewer.displays.image_sender.LatestImageSender`, which JPEG-encodes the
newest on a thread of its own, and viser replaces an image update the page has not taken yet
by the next one, so neither the encoder nor a slow page ever holds a backlog.
"""

from __future__ import annotations

import time
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    register_display,
)
from robomodel.viewer.displays.image import (
    ImageError,
    RangeNormalizer,
    compressed_image_rgb,
    image_pil,
    image_rgb,
    upscaled_pil,
)
from robomodel.viewer.displays.image_sender import JPEG_QUALITY, LatestImageSender
from robomodel.viewer.limits import MAX_IMAGE_PIXELS

if TYPE_CHECKING:  # Pillow comes with the viewer extra; a headless launch imports no image code
    from PIL import Image

__all__ = ["BURST_FRAMES", "FramePacer", "ImageDisplay", "message_pil", "message_rgb"]

BURST_FRAMES = 3.0  # frames of unused budget kept (see the module docstring)
PANEL_MIN_SIDE = 320  # a smaller image is shown with its pixels repeated to fill the panel
_DOCK_ORDER = -1000.0  # viser orders the panel's folders by this: image areas come first

IMAGE_OPTIONS = (
    Option(
        "Normalize Range",
        True,
        OptionKind.BOOL,
        help="If set to true, will try to estimate the range of possible values from the received images.",
    ),
    Option("Min Value", 0.0, OptionKind.FLOAT, help="Value which will be displayed as black."),
    Option("Max Value", 1.0, OptionKind.FLOAT, help="Value which will be displayed as white."),
    Option(
        "Median window",
        5,
        OptionKind.INT,
        minimum=1,
        help="Window size for median filter used for computing min/max.",
    ),
)


def _normalization(values: dict[str, Any], normalizer: RangeNormalizer) -> dict[str, Any]:
    normalizer.median_window = int(values["Median window"])
    return {
        "normalize": bool(values["Normalize Range"]),
        "min_value": float(values["Min Value"]),
        "max_value": float(values["Max Value"]),
        "normalizer": normalizer,
    }


def message_rgb(msg: Any, values: dict[str, Any], normalizer: RangeNormalizer) -> NDArray[np.uint8]:
    """An Image or CompressedImage as RGB with the display's normalisation options."""
    kwargs = _normalization(values, normalizer)
    if hasattr(msg, "format"):  # sensor_msgs/CompressedImage
        return compressed_image_rgb(msg, **kwargs)
    return image_rgb(msg, **kwargs)


def message_pil(msg: Any, values: dict[str, Any], normalizer: RangeNormalizer) -> Image.Image:
    """An Image or CompressedImage as a Pillow image (RGB, or L for grey encodings) with the
    display's normalisation options."""
    if hasattr(msg, "format"):  # sensor_msgs/CompressedImage
        from PIL import Image

        return Image.fromarray(message_rgb(msg, values, normalizer))
    return image_pil(msg, **_normalization(values, normalizer))


class FramePacer:
    """At most ``rate_hz`` events a second on average, up to :data:`BURST_FRAMES` at once
    (a token bucket, refilled at the rate, that starts full)."""

    def __init__(self) -> None:
        self._budget = BURST_FRAMES
        self._last_s: float | None = None

    def allow(self, now_s: float, rate_hz: float) -> bool:
        """Whether an event at ``now_s`` [s, monotonic] fits the rate (and spend it if so)."""
        if self._last_s is not None:
            self._budget = min(BURST_FRAMES, self._budget + (now_s - self._last_s) * rate_hz)
        self._last_s = now_s
        if self._budget < 1.0:
            return False
        self._budget -= 1.0
        return True


@register_display
class ImageDisplay(Display):
    """RViz's Image display: the image in an image area of its own."""

    class_name = "Image"
    message_types = ("sensor_msgs/msg/Image", "sensor_msgs/msg/CompressedImage")
    options: ClassVar[tuple[Option, ...]] = (
        Option("Topic", "", OptionKind.TOPIC, help="sensor_msgs/Image topic"),
        Option("Queue Size", 5, OptionKind.INT, minimum=0, help="Incoming message queue"),
        *IMAGE_OPTIONS,
    )
    # RViz 1's ImageDisplayBase (rviz/image/image_display_base.cpp) names it "Image Topic"
    ros1_keys = MappingProxyType({"Topic": "Image Topic"})

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._pending: Any = None
        self._normalizer = RangeNormalizer()
        self._error = ""
        self.sender: LatestImageSender | None = None  # to the image area, once built
        self._dock: Any = None
        self._pacer = FramePacer()
        self._shown: Image.Image | None = None  # the image shown, at its own size
        self._rgb: NDArray[np.uint8] | None = None  # it as an RGB array, made when asked for
        self.header: Any = None  # the shown image's header
        self.shown = 0  # images converted and shown
        self.skipped = 0  # images replaced by a newer one before they were converted
        self._full_rows = 0  # rows of the last image converted (more than shown: truncated)

    @property
    def rgb(self) -> NDArray[np.uint8] | None:
        """The image shown as (height, width, 3) RGB, or None before the first."""
        if self._rgb is None and self._shown is not None:
            self._rgb = np.asarray(self._shown.convert("RGB"))
        return self._rgb

    @property
    def sent(self) -> int:
        """Images JPEG-encoded and handed to the page (fewer than shown: the encoder skipped
        older ones while it was busy)."""
        return self.sender.sent if self.sender is not None else 0

    def on_message(self, msg: Any) -> None:
        if self._pending is not None:
            self.skipped += 1
        self._pending = msg
        if self.enabled:
            self.show_pending()

    def build_dock(self, gui: Any) -> None:
        placeholder = np.full((48, 64, 3), 40, dtype=np.uint8)  # RViz's empty texture: dark
        self._dock = gui.add_folder(self.name, order=_DOCK_ORDER, expand_by_default=True,
                                    visible=self.enabled)  # fmt: skip
        with self._dock:
            # JPEG as RViz's image_transport "compressed" would: PNG of a 640x480 camera
            # image is ~10x larger and slower to encode
            handle = gui.add_image(placeholder, format="jpeg", jpeg_quality=JPEG_QUALITY)
        self.sender = LatestImageSender(handle, name=self.name)

    def on_renamed(self) -> None:
        super().on_renamed()
        if self._dock is not None:
            self._dock.label = self.name

    def on_enabled_changed(self) -> None:
        super().on_enabled_changed()
        if self._dock is not None:
            self._dock.visible = self.enabled

    def on_option_changed(self, name: str) -> None:
        if name == "Topic":
            self.messages_received = 0
            self._pending, self._shown, self._rgb = None, None, None
            if self.sender is not None:
                self.sender.discard()
        self._normalizer = RangeNormalizer(int(self.values["Median window"]))

    def close(self) -> None:
        super().close()
        if self.sender is not None:
            self.sender.close()  # before the handle goes: nothing is set on it after
            self.sender = None
        if self._dock is not None:
            self._dock.remove()
            self._dock = None

    def convert_pending(self) -> Image.Image | None:
        """The newest image (RGB or L) if one came since the last one shown, else None."""
        msg, self._pending = self._pending, None
        if msg is None:
            return None
        try:
            image = message_pil(msg, self.values, self._normalizer)
        except ImageError as exc:
            self._error = str(exc)
            return None
        self._error = ""
        self.shown += 1
        self._shown, self._rgb = image, None
        self.header = getattr(msg, "header", None)
        self._full_rows = int(getattr(msg, "height", 0) or image.height)
        return image

    def show_pending(self) -> bool:
        """Convert the newest image and hand it to the panel if the Frame Rate allows one
        more now; whether one was shown."""
        if self._pending is None:
            return False
        if not self._pacer.allow(time.monotonic(), float(self.context.frame_rate_hz())):
            return False
        image = self.convert_pending()
        if image is None:
            return False
        if self.sender is not None:
            self.sender.submit(upscaled_pil(image, min_side=PANEL_MIN_SIDE))
        return True

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        self.show_pending()
        if self._error:
            return DisplayStatus.error(self._error)
        waiting = self.topic_status()
        if waiting is not None or self._shown is None:
            return waiting or DisplayStatus.ok()
        w, h = self._shown.size
        text = f"{self.messages_received} images received; showing {w}x{h}"
        if self._full_rows > h:
            return DisplayStatus.warn(
                f"{text}: an image of {w}x{self._full_rows} drawn truncated to its first {h} "
                f"rows ({MAX_IMAGE_PIXELS} pixels at most)"
            )
        return DisplayStatus.ok(text)
