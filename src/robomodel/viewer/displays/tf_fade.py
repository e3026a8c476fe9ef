"""How RViz's TF display draws a frame as it ages: normal, then grey, then gone.

Transcribed from ros2/rviz at f7112b1, rviz_default_plugins/src/rviz_default_plugins/displays/
tf/frame_info.cpp, ``FrameInfo::updateColorForAge`` (lines 172-207): with ``third`` =
``frame_timeout * 0.3333333``, a frame up to ``third`` old has its default colours; up to
``2 * third`` each colour is ``lerpColor(default, grey, t) = default * t + grey * (1 - t)``
with ``t = (2 * third - age) / third`` (grey = (0.7, 0.7, 0.7, 1)); past that it is grey with
alpha ``max(0, (frame_timeout - age) / third)``. ``TFDisplay::updateFrame`` (tf_display.cpp
lines 466-472) hides a frame older than Frame Timeout; its age is the time since its latest
common time with the fixed frame (tf_display.cpp lines 449-464) last changed, and a frame
joined to it by static transforms only (time zero) never ages (``FrameInfo::setLastUpdate``,
frame_info.cpp lines 164-170).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["AXES_RGBA", "GREY_RGBA", "HEAD_RGBA", "NAME_RGBA", "SHAFT_RGBA", "aged_rgba", "rgb8"]

GREY_RGBA = (0.7, 0.7, 0.7, 1.0)
# rviz_rendering Axes::default_{x,y,z}_color_ (axes.cpp lines 150-152)
AXES_RGBA = ((1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0))
NAME_RGBA = (1.0, 1.0, 1.0, 1.0)  # Ogre::ColourValue::White
SHAFT_RGBA = (0.8, 0.8, 0.3, 1.0)  # FrameInfo::ARROW_SHAFT_COLOR (frame_info.cpp line 63)
HEAD_RGBA = (1.0, 0.1, 0.6, 1.0)  # FrameInfo::ARROW_HEAD_COLOR (frame_info.cpp line 62)


def aged_rgba(defaults: ArrayLike, age_s: ArrayLike, timeout_s: float) -> NDArray[np.float64]:
    """The colours RViz draws for frames ``age_s`` old, given their fresh colours.

    Args:
        defaults: Shape (k, 4): a fresh frame's colours (RGBA, 0..1), e.g. :data:`AXES_RGBA`.
        age_s: Shape (n,): each frame's age [s] (0 for a static frame).
        timeout_s: The display's Frame Timeout [s].

    Returns:
        Shape (n, k, 4): each frame's colours. Alpha is 0 from ``timeout_s`` on, where RViz
        no longer draws the frame.
    """
    fresh = np.asarray(defaults, dtype=np.float64).reshape(-1, 4)
    age = np.asarray(age_s, dtype=np.float64).reshape(-1, 1, 1)
    third = timeout_s * 0.3333333
    grey = np.asarray(GREY_RGBA)
    t = np.clip((2.0 * third - age) / third, 0.0, 1.0)  # 1 up to one third, 0 from two thirds
    rgba = fresh * t + grey * (1.0 - t)
    alpha = np.clip((timeout_s - age[..., 0]) / third, 0.0, 1.0)
    fading = age[..., 0] > 2.0 * third
    rgba[..., 3] = np.where(fading, alpha, rgba[..., 3])
    return rgba


def rgb8(rgba: NDArray[np.float64]) -> NDArray[np.uint8]:
    """The RGB channels of ``rgba`` (0..1, shape (..., 4)) as 0..255, halves rounded up."""
    return np.floor(np.asarray(rgba)[..., :3] * 255 + 0.5).astype(np.uint8)
