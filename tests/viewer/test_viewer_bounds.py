"""What a peer publishes is drawn within the bounds of ``robomodel.viewer.limits``.

A 10,000-character TEXT_VIEW_FACING marker used to become a 63x460,004 RGBA image (430 MB at
its peak); markers of millions of points, floods of marker ids, clouds declaring 10^9 points and
images of millions of pixels are each cut to their bound (the first part drawn, the status
saying so) or refused before anything large is built.
"""

from __future__ import annotations

import io
import time
import tracemalloc

import numpy as np
import pytest

from robomodel.viewer import limits
from robomodel.viewer.displays import StatusLevel, display_class, marker_geometry, marker_store
from robomodel.viewer.displays import cloud as cloud_module
from robomodel.viewer.displays import image as image_module
from robomodel.viewer.displays.cloud import CloudError, cloud_records, decode_cloud
from robomodel.viewer.displays.image import ImageError, compressed_image_rgb, image_rgb
from tests.viewer.fake_scene import FakeClock, FakeScene, fake_context, lookup_from
from tests.viewer.test_cloud_convert import XYZ, PointCloud2, PointField, make_cloud
from tests.viewer.test_image_convert import CompressedImage, make_image
from tests.viewer.test_markers import MarkerArray, Point, marker

IDENTITY = lookup_from({"base_link": np.eye(4)})


def _display(kind: str = "rviz/Marker") -> tuple[FakeScene, object]:
    scene = FakeScene()
    return scene, display_class(kind)(kind, fake_context(scene, clock=FakeClock()))


def test_a_long_text_marker_is_drawn_truncated_in_bounded_time_and_memory() -> None:
    scene, display = _display()
    text = marker(type_=9)
    text.text = "W" * 10_000  # type: ignore[attr-defined]
    display.receive(text)  # type: ignore[attr-defined]
    tracemalloc.start()
    start = time.perf_counter()
    status = display.draw(IDENTITY)  # type: ignore[attr-defined]
    elapsed_s = time.perf_counter() - start
    peak_bytes = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    (node,) = scene.visible("/displays/").values()
    height_px, width_px = node.kwargs["image"].shape[:2]
    assert height_px * width_px <= 4_000_000, (width_px, height_px)  # was 63x460,004
    assert peak_bytes < 64 * 2**20 and elapsed_s < 2.0, (peak_bytes, elapsed_s)
    assert status.level is StatusLevel.WARN
    assert status.text == (
        "/0: text of 10000 characters in 1 lines drawn truncated to 1000 characters and 100 lines"
    )


def test_many_text_lines_are_cut_too() -> None:
    shown, note = limits.truncated_text("a\n" * 500)
    assert shown.count("\n") == limits.MAX_TEXT_LINES - 1 and shown.endswith("…")
    assert "501 lines" in note
    assert limits.truncated_text("short\ntext") == ("short\ntext", "")


def test_a_marker_of_too_many_points_draws_its_first_points(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(marker_geometry, "MAX_MARKER_POINTS", 100)
    scene, display = _display()
    points = marker(type_=8)
    points.points = [Point(x=float(k)) for k in range(150)]  # type: ignore[attr-defined]
    display.receive(points)  # type: ignore[attr-defined]
    status = display.draw(IDENTITY)  # type: ignore[attr-defined]
    (node,) = scene.visible("/displays/").values()
    assert node.kwargs["points"].shape == (100, 3)
    assert node.kwargs["points"][-1, 0] == 99.0  # the first 100, in order
    assert status.level is StatusLevel.WARN
    assert status.text == "/0: 150 points drawn truncated to the first 100"


def test_marker_ids_past_the_namespace_bound_are_not_drawn(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(marker_store, "MAX_MARKERS_PER_NAMESPACE", 5)
    scene, display = _display("rviz/MarkerArray")
    flood = MarkerArray(markers=[marker("a", k) for k in range(10)] + [marker("b", 0)])
    display.receive(flood)  # type: ignore[attr-defined]
    status = display.draw(IDENTITY)  # type: ignore[attr-defined]
    assert len(scene.visible("/displays/")) == 6  # a/0..a/4 and b/0
    assert status.level is StatusLevel.WARN
    assert status.text.startswith("a: more than 5 markers in the namespace; new ids are not drawn")
    # a marker already held is still updated, and a deleted one makes room
    display.receive(MarkerArray(markers=[marker("a", 0, action=2), marker("a", 7)]))  # type: ignore[attr-defined]
    display.draw(IDENTITY)  # type: ignore[attr-defined]
    assert set(display.store.markers) == {("a", k) for k in (1, 2, 3, 4, 7)} | {("b", 0)}  # type: ignore[attr-defined]


def test_a_cloud_declaring_a_billion_points_with_little_data_is_refused_cheaply() -> None:
    msg = PointCloud2(
        height=1000, width=1_000_000, point_step=12, row_step=12_000_000,
        fields=[PointField(name=n, offset=o, datatype=d, count=1) for n, o, d in XYZ],
        data=list(bytes(120)),
    )  # fmt: skip
    tracemalloc.start()
    with pytest.raises(CloudError, match=r"^Data size \(120 bytes\) does not match width"):
        cloud_records(msg)
    assert tracemalloc.get_traced_memory()[1] < 2**20
    tracemalloc.stop()


def test_a_cloud_over_the_bound_draws_its_first_points(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(cloud_module, "MAX_CLOUD_POINTS", 10)
    cloud = make_cloud([(float(k), 0.0, 0.0) for k in range(25)], XYZ, "fff")
    decoded = decode_cloud(cloud)
    assert decoded.points_m.shape == (10, 3) and decoded.truncated == 15
    assert decoded.points_m[-1, 0] == 9.0


def test_a_raw_image_over_the_bound_is_drawn_as_its_first_rows(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setattr(image_module, "MAX_IMAGE_PIXELS", 40)
    pixels = np.arange(10 * 8 * 3, dtype=np.uint8).reshape(10, 8, 3)
    out = image_rgb(make_image(pixels, "rgb8"))
    assert out.shape == (5, 8, 3)  # 40 pixels: 5 rows of 8
    np.testing.assert_array_equal(out, pixels[:5])
    with pytest.raises(ImageError, match="a row is wider than the 40 pixels"):
        image_rgb(make_image(np.zeros((1, 41, 3), np.uint8), "rgb8"))


def test_a_compressed_image_over_the_bound_is_refused_before_it_is_decoded() -> None:
    from PIL import Image as PilImage

    buffer = io.BytesIO()
    PilImage.new("L", (5000, 4000)).save(buffer, format="PNG")  # 20 Mpx in ~20 KB
    msg = CompressedImage(format="png", data=buffer.getvalue())
    tracemalloc.start()
    with pytest.raises(ImageError, match=r"5000x4000 pixels is larger than the 16777216 pixels"):
        compressed_image_rgb(msg)
    assert tracemalloc.get_traced_memory()[1] < 8 * 2**20
    tracemalloc.stop()
