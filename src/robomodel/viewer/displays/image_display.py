"""RViz's Image display: the latest sensor_msgs/Image (or CompressedImage) as a panel image.

RViz 2's Image display (image_display.cpp) shows the image in its own panel, with "Normalize
Range", "Min Value", "Max Value" and "Median window" for 16-bit and float images; a topic of
type CompressedImage (image_transport's ``.../compressed``) is decoded as RViz's compressed
transport would. Only the newest image is converted, when the page is next drawn (10 Hz):
older ones are skipped, as RViz shows the newest at each render.
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Any, ClassVar

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
    image_rgb,
    nearest_upscale,
)
from robomodel.viewer.limits import MAX_IMAGE_PIXELS

__all__ = ["ImageDisplay", "message_rgb"]

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


def message_rgb(msg: Any, values: dict[str, Any], normalizer: RangeNormalizer) -> NDArray[np.uint8]:
    """An Image or CompressedImage as RGB with the display's normalisation options."""
    normalizer.median_window = int(values["Median window"])
    kwargs: dict[str, Any] = {
        "normalize": bool(values["Normalize Range"]),
        "min_value": float(values["Min Value"]),
        "max_value": float(values["Max Value"]),
        "normalizer": normalizer,
    }
    if hasattr(msg, "format"):  # sensor_msgs/CompressedImage
        return compressed_image_rgb(msg, **kwargs)
    return image_rgb(msg, **kwargs)


@register_display
class ImageDisplay(Display):
    """RViz's Image display: the image in the display's folder of the panel."""

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
        self._panel_image: Any = None
        self.rgb: NDArray[np.uint8] | None = None  # the image shown
        self.header: Any = None  # the shown image's header
        self.shown = 0  # images converted and shown
        self._full_rows = 0  # rows of the last image converted (more than shown: truncated)

    def on_message(self, msg: Any) -> None:
        self._pending = msg

    def build_panel(self, gui: Any) -> None:
        placeholder = np.full((48, 64, 3), 40, dtype=np.uint8)  # RViz's empty texture: dark
        # JPEG as RViz's image_transport "compressed" would: PNG of a 640x480 camera image
        # is ~10x larger and slower to encode
        self._panel_image = gui.add_image(
            placeholder, label=self.name, format="jpeg", jpeg_quality=90
        )

    def on_option_changed(self, name: str) -> None:
        if name == "Topic":
            self.messages_received = 0
            self._pending, self.rgb = None, None
        self._normalizer = RangeNormalizer(int(self.values["Median window"]))

    def close(self) -> None:
        super().close()
        if self._panel_image is not None:
            self._panel_image.remove()
            self._panel_image = None

    def convert_pending(self) -> bool:
        """Convert the newest image if one came since the last draw; whether one did."""
        msg, self._pending = self._pending, None
        if msg is None:
            return False
        try:
            self.rgb = message_rgb(msg, self.values, self._normalizer)
        except ImageError as exc:
            self._error = str(exc)
            return False
        self._error = ""
        self.shown += 1
        self.header = getattr(msg, "header", None)
        self._full_rows = int(getattr(msg, "height", 0) or self.rgb.shape[0])
        return True

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        if self.convert_pending() and self._panel_image is not None and self.rgb is not None:
            # a small image is shown at its own size: repeat its pixels to fill the panel
            self._panel_image.image = nearest_upscale(self.rgb, min_side=320)
        if self._error:
            return DisplayStatus.error(self._error)
        waiting = self.topic_status()
        if waiting is not None or self.rgb is None:
            return waiting or DisplayStatus.ok()
        h, w = self.rgb.shape[:2]
        text = f"{self.messages_received} images received; showing {w}x{h}"
        if self._full_rows > h:
            return DisplayStatus.warn(
                f"{text}: an image of {w}x{self._full_rows} drawn truncated to its first {h} "
                f"rows ({MAX_IMAGE_PIXELS} pixels at most)"
            )
        return DisplayStatus.ok(text)
