"""sensor_msgs/Image and CompressedImage -> RGB (robomodel.viewer.displays.image): a 4x4
checkerboard in every encoding, row padding, byte order, normalisation and compressed forms."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image as PILImage

from robomodel.runtime.msg import deserialize, get_message_type, serialize
from robomodel.viewer.displays.image import (
    ImageError,
    RangeNormalizer,
    compressed_image_rgb,
    image_pil,
    image_rgb,
)

Image = get_message_type("sensor_msgs/msg/Image")
CompressedImage = get_message_type("sensor_msgs/msg/CompressedImage")

RED, BLUE = (255, 0, 0), (0, 0, 255)
BOARD = np.indices((4, 4)).sum(axis=0) % 2 == 0  # True where the checker is "on"
EXPECTED_RB = np.where(BOARD[..., None], RED, BLUE).astype(np.uint8)


def make_image(pixels: np.ndarray, encoding: str, *, pad: int = 0, big: bool = False) -> object:
    h, w = pixels.shape[:2]
    rows = pixels.reshape(h, -1).view(np.uint8).reshape(h, -1)
    rows = np.concatenate([rows, np.full((h, pad), 0xAB, np.uint8)], axis=1)
    msg = Image(height=h, width=w, encoding=encoding, is_bigendian=big, step=rows.shape[1], data=list(rows.tobytes()))  # fmt: skip
    return deserialize(serialize(msg), Image)


@pytest.mark.parametrize(
    ("encoding", "channels"),
    [("rgb8", (0, 1, 2)), ("bgr8", (2, 1, 0)), ("8UC3", (2, 1, 0)), ("rgba8", (0, 1, 2, None)),
     ("bgra8", (2, 1, 0, None)), ("8UC4", (2, 1, 0, None))],
)  # fmt: skip
def test_colour_checkerboards(encoding: str, channels: tuple[int | None, ...]) -> None:
    layers = [EXPECTED_RB[..., c] if c is not None else np.full((4, 4), 77, np.uint8) for c in channels]  # fmt: skip
    pixels = np.stack(layers, axis=-1)
    np.testing.assert_array_equal(image_rgb(make_image(pixels, encoding)), EXPECTED_RB)
    np.testing.assert_array_equal(image_rgb(make_image(pixels, encoding, pad=5)), EXPECTED_RB)


@pytest.mark.parametrize("encoding", ["mono8", "8UC1", "bayer_rggb8"])
def test_mono8_checkerboard(encoding: str) -> None:
    pixels = np.where(BOARD, 200, 10).astype(np.uint8)
    out = image_rgb(make_image(pixels, encoding, pad=3))
    np.testing.assert_array_equal(out, np.repeat(pixels[..., None], 3, axis=2))


@pytest.mark.parametrize(("encoding", "dtype"), [("mono16", "<u2"), ("16UC1", "<u2"), ("32FC1", "<f4")])  # fmt: skip
def test_scaled_checkerboards_normalised(encoding: str, dtype: str) -> None:
    pixels = np.where(BOARD, 3000, 1000).astype(dtype)
    out = image_rgb(make_image(pixels, encoding))
    np.testing.assert_array_equal(out[..., 0], np.where(BOARD, 255, 0))
    big = image_rgb(make_image(pixels.astype(dtype.replace("<", ">")), encoding, big=True))
    np.testing.assert_array_equal(big, out)


def test_scaled_with_fixed_range_and_nan() -> None:
    pixels = np.array([[0.0, 0.5], [2.0, np.nan]], dtype="<f4")
    out = image_rgb(make_image(pixels, "32FC1"), normalize=False, min_value=0.0, max_value=1.0)
    np.testing.assert_array_equal(out[..., 1], [[0, 127], [255, 0]])
    out = image_rgb(make_image(pixels, "32FC1"))  # normalised over the finite values 0..2
    np.testing.assert_array_equal(out[..., 1], [[0, 63], [255, 0]])


def test_median_window_keeps_range_over_an_outlier_frame() -> None:
    normalizer = RangeNormalizer(median_window=3)
    steady = np.array([[1000, 2000]], dtype="<u2")
    for _ in range(2):
        image_rgb(make_image(steady, "16UC1"), normalizer=normalizer)
    outlier = np.array([[1000, 60000]], dtype="<u2")
    out = image_rgb(make_image(outlier, "16UC1"), normalizer=normalizer)
    np.testing.assert_array_equal(out[0, :, 0], [0, 255])  # scaled over 1000..2000 still
    assert normalizer.bounds(0, 1) == (1000, 2000)  # window: the last three frames


def test_yuv422_matches_rviz_formula() -> None:
    # one UYVY quad: u=90, y0=100, v=200, y1=50 -> RViz: r = y + 1403*72/1000 (=101) ...
    msg = make_image(np.array([[[90, 100, 200, 50]]], np.uint8).reshape(1, 2, 2), "yuv422")
    out = image_rgb(msg)
    for k, y in enumerate((100, 50)):
        r = y + int(1403 * 72 / 1000)
        g = y + int((344 * -38 - 714 * 72) / 1000)
        b = y + int(1770 * -38 / 1000)
        assert tuple(out[0, k]) == tuple(np.clip([r, g, b], 0, 255))


def test_unknown_encoding_and_short_data_are_errors() -> None:
    with pytest.raises(ImageError, match=r"Unsupported image encoding \[rgb16\]; supported"):
        image_rgb(make_image(np.zeros((2, 2, 6), np.uint8), "rgb16"))
    msg = make_image(np.zeros((4, 4, 3), np.uint8), "rgb8")
    msg.height = 5
    with pytest.raises(ImageError, match="needs 12 bytes a row"):
        image_rgb(msg)


@pytest.mark.parametrize("fmt", ["png", "jpeg"])
def test_compressed_checkerboard(fmt: str) -> None:
    big = np.kron(EXPECTED_RB, np.ones((8, 8, 1), np.uint8))  # 32x32: JPEG blocks stay clean
    buf = io.BytesIO()
    PILImage.fromarray(big).save(buf, format=fmt.upper(), quality=95)
    msg = CompressedImage(format=f"rgb8; {fmt} compressed rgb8", data=list(buf.getvalue()))
    out = compressed_image_rgb(deserialize(serialize(msg), CompressedImage))
    assert out.shape == (32, 32, 3)
    centres = out[4::8, 4::8].astype(int)
    assert np.abs(centres - EXPECTED_RB).max() <= (0 if fmt == "png" else 20)


def test_compressed_depth_png_and_garbage() -> None:
    depth = np.where(BOARD, 4000, 500).astype(np.uint16)
    buf = io.BytesIO()
    PILImage.fromarray(depth).save(buf, format="PNG")
    header = bytes(12)  # compressed_depth_image_transport's ConfigHeader
    msg = CompressedImage(format="16UC1; compressedDepth png", data=list(header + buf.getvalue()))
    out = compressed_image_rgb(msg)
    np.testing.assert_array_equal(out[..., 2], np.where(BOARD, 255, 0))
    with pytest.raises(ImageError, match="cannot decode compressed image"):
        compressed_image_rgb(CompressedImage(format="jpeg", data=list(b"not an image")))


@pytest.mark.parametrize(
    ("encoding", "pixels"),
    [("rgb8", EXPECTED_RB), ("bgr8", EXPECTED_RB[..., ::-1]), ("8UC3", EXPECTED_RB[..., ::-1]),
     ("mono8", np.where(BOARD, 200, 10).astype(np.uint8)), ("8UC1", np.where(BOARD, 200, 10).astype(np.uint8)),
     ("bayer_rggb8", np.where(BOARD, 200, 10).astype(np.uint8)), ("rgba8", np.dstack([EXPECTED_RB, np.full((4, 4), 9, np.uint8)])),
     ("mono16", np.where(BOARD, 3000, 1000).astype("<u2"))],
)  # fmt: skip
@pytest.mark.parametrize("pad", [0, 5])
def test_pillow_image_has_image_rgb_s_pixels(encoding: str, pixels: np.ndarray, pad: int) -> None:
    """The panel's Pillow image (unpacked by Pillow from the message's bytes for 8-bit RGB, BGR
    and grey) holds exactly the pixels image_rgb gives, row padding skipped; upscaled, each
    pixel repeated."""
    msg = make_image(pixels, encoding, pad=pad)
    image = image_pil(msg)
    assert image.mode == ("L" if pixels.ndim == 2 and encoding != "mono16" else "RGB")
    np.testing.assert_array_equal(np.asarray(image.convert("RGB")), image_rgb(msg))
    big = np.asarray(image_pil(msg, min_side=320).convert("RGB"))
    assert big.shape == (320, 320, 3)
    np.testing.assert_array_equal(big[::80, ::80], image_rgb(msg))
