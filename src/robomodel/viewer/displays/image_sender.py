"""The newest image to a viser GUI image area, JPEG-encoded on a thread of its own.

RViz draws the newest image at each render and never queues older ones. The Image display
hands each image it shows (at most one per frame of the Frame Rate) to a
:class:`LatestImageSender`, which keeps at most one image waiting: an image handed over while
the previous one is still being encoded replaces the one waiting (counted in ``replaced``), so
neither a slow encoder nor a slow page builds a backlog, and memory stays at two images. Past
the encoder, viser replaces an image update the page has not taken yet by the next one.

The JPEG is made with Pillow (libjpeg-turbo in its wheels), which releases the GIL while it
encodes: on its own thread the encoding runs beside the viewer's loop thread instead of
holding it. viser's ``GuiImageHandle.image`` setter would encode through imageio (or OpenCV,
which robomodel does not require), about 8 ms for a 640x480 camera image against Pillow's 1 ms,
and retries ``import cv2`` through every import finder at each image; the display sets the
encoded bytes on the handle instead (viser 1.x's ``GuiImageProps._data``/``_format``).
"""

from __future__ import annotations

import io
import logging
import threading
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # Pillow comes with the viewer extra; a headless launch imports no image code
    from PIL.Image import Image

__all__ = ["IDLE_EXIT_S", "JPEG_QUALITY", "LatestImageSender", "encode_jpeg"]

# image_transport's "compressed" default is 80; 90 keeps text and edges in a camera image crisp
JPEG_QUALITY = 90
IDLE_EXIT_S = 2.0  # the thread ends after this long without an image (the next one starts it)

log = logging.getLogger("robomodel.viewer")


def encode_jpeg(image: Image, quality: int = JPEG_QUALITY) -> bytes:
    """``image`` (mode RGB or L) as JPEG bytes."""
    out = io.BytesIO()
    image.save(out, format="JPEG", quality=quality)
    return out.getvalue()


class LatestImageSender:
    """Encodes the newest image handed to :meth:`submit` and sets it on a viser GUI image
    handle, on a daemon thread that runs while images come (started by an image, ended after
    :data:`IDLE_EXIT_S` without one); older images waiting are replaced.

    Attributes:
        sent: Images encoded and set on the handle.
        replaced: Images replaced by a newer one before they were encoded.
    """

    def __init__(self, handle: Any, *, name: str = "image", jpeg_quality: int = JPEG_QUALITY) -> None:  # fmt: skip
        self._handle = handle
        self._name = name
        self._quality = jpeg_quality
        self._cond = threading.Condition()  # guards the image waiting and the flags
        self._handle_lock = threading.Lock()  # held while an image is set on the handle
        self._waiting: Image | None = None
        self._busy = False
        self._closed = False
        self._thread: threading.Thread | None = None
        self.sent = 0
        self.replaced = 0

    @property
    def running(self) -> bool:
        """Whether the encoding thread is alive (images came within :data:`IDLE_EXIT_S`)."""
        with self._cond:
            return self._thread is not None

    def submit(self, image: Image) -> None:
        """Send ``image`` as soon as the encoder is free, instead of any image still waiting."""
        with self._cond:
            if self._closed:
                return
            if self._waiting is not None:
                self.replaced += 1
            self._waiting = image
            if self._thread is None:
                self._thread = threading.Thread(
                    target=self._run, name=f"robomodel-view-image {self._name}", daemon=True
                )
                self._thread.start()
            self._cond.notify_all()

    def discard(self) -> None:
        """Forget the image waiting, if any (not counted as replaced: nothing newer came)."""
        with self._cond:
            self._waiting = None

    def flush(self, timeout_s: float) -> bool:
        """Wait until no image waits or is being encoded; whether that happened in time."""
        with self._cond:
            return self._cond.wait_for(
                lambda: self._waiting is None and not self._busy, timeout=timeout_s
            )

    def close(self) -> None:
        """Stop: nothing is set on the handle after this returns (the handle can be removed)."""
        with self._cond:
            self._closed, self._waiting = True, None
            self._cond.notify_all()
        with self._handle_lock:  # an image being set is set before this returns
            pass

    def _run(self) -> None:
        while True:
            with self._cond:
                self._cond.wait_for(
                    lambda: self._waiting is not None or self._closed, timeout=IDLE_EXIT_S
                )
                image = self._waiting
                if self._closed or image is None:  # closed, or idle: submit() starts another
                    self._thread = None
                    return
                self._waiting, self._busy = None, True
            try:
                data = encode_jpeg(image, self._quality)
                with self._handle_lock:  # close() waits for this: no image on a removed handle
                    if not self._closed:
                        self._handle._format = "jpeg"  # unchanged: viser sends nothing
                        self._handle._data = data
                        self.sent += 1
            except Exception:  # the display goes on with the next image
                log.exception("image display %s: the image could not be sent", self._name)
            finally:
                with self._cond:
                    self._busy = False
                    self._cond.notify_all()
