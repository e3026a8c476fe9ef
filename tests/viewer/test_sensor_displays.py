"""The PointCloud2, Image, Camera and Map displays on a fake scene (no browser): what they
draw, where, and their statuses."""

from __future__ import annotations

import io
import struct
import threading

import numpy as np
import pytest
from PIL import Image as PILImage

from robomodel.runtime.msg import get_message_type
from robomodel.viewer.displays import display_class
from robomodel.viewer.displays.camera import camera_info_topic
from robomodel.viewer.displays.image_sender import LatestImageSender
from tests.timing import scaled, wait_until
from tests.viewer.fake_scene import FakeClock, FakeScene, fake_context, lookup_from

PointCloud2 = get_message_type("sensor_msgs/msg/PointCloud2")
PointField = get_message_type("sensor_msgs/msg/PointField")


def three_point_cloud(frame: str = "lidar", stamp_s: int = 0) -> object:
    """Red at (1, 0, 0), green at (0, 1, 0), blue at (0, 0, 1), rgb packed as PCL does."""
    rows = [((1.0, 0.0, 0.0), 0xFF0000), ((0.0, 1.0, 0.0), 0x00FF00), ((0.0, 0.0, 1.0), 0x0000FF)]
    data = b"".join(struct.pack("<fff4xI", *p, c) for p, c in rows)
    msg = PointCloud2(height=1, width=3, point_step=20, row_step=60, data=list(data), is_dense=True)
    msg.fields = [PointField(name=n, offset=o, datatype=d, count=1)
                  for n, o, d in (("x", 0, 7), ("y", 4, 7), ("z", 8, 7), ("rgb", 16, 7))]  # fmt: skip
    msg.header.frame_id = frame
    msg.header.stamp.sec = stamp_s
    return msg


def shifted(x: float) -> np.ndarray:
    T = np.eye(4)
    T[0, 3] = x
    return T


def test_point_cloud2_places_points_through_tf_with_rgb_and_status() -> None:
    scene = FakeScene()
    display = display_class("PointCloud2")("cloud", fake_context(scene), {"Topic": "/points"})
    status = display.draw(lookup_from({}))
    assert status.text == "No messages received"
    display.receive(three_point_cloud())
    status = display.draw(lookup_from({}))
    assert status.level.value == "error" and "No transform from [lidar] to [map]" in status.text
    assert not scene.visible("/displays/cloud")
    status = display.draw(lookup_from({"lidar": shifted(2.0)}))
    assert status.text == "Showing [3] points from [1] messages"
    (node,) = scene.visible("/displays/cloud").values()
    assert node.kind == "point_cloud" and node.position == (2.0, 0.0, 0.0)
    np.testing.assert_array_equal(node.kwargs["colors"], [[255, 0, 0], [0, 255, 0], [0, 0, 255]])
    np.testing.assert_array_equal(node.kwargs["points"], np.eye(3, dtype=np.float32))
    assert node.kwargs["point_size"] == 0.01
    assert display.option("Color Transformer") == "RGB8"  # chosen for a cloud with rgb


def test_point_cloud2_decay_time_keeps_recent_clouds() -> None:
    scene, clock = FakeScene(), FakeClock()
    values = {"Topic": "/points", "Decay Time": 1.0, "Size (m)": 0.2}
    display = display_class("PointCloud2")("cloud", fake_context(scene, clock=clock), values)
    lookup = lookup_from({"lidar": np.eye(4)})
    for _ in range(3):
        display.receive(three_point_cloud())
        display.draw(lookup)
        clock.ns += 300_000_000
    assert display.draw(lookup).text == "Showing [9] points from [3] messages"
    clock.ns += 200_000_000  # the first is now 1.1 s old
    assert display.draw(lookup).text == "Showing [6] points from [2] messages"
    display.set_option("Decay Time", 0.0)
    display.receive(three_point_cloud())
    assert display.draw(lookup).text == "Showing [3] points from [1] messages"
    assert len(scene.visible("/displays/cloud")) == 1
    assert next(iter(scene.nodes.values())).kwargs["point_size"] == 0.2


def test_point_cloud2_decay_time_keeps_clouds_within_the_bound(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from robomodel.viewer.displays import point_cloud2

    monkeypatch.setattr(point_cloud2, "MAX_CLOUDS_KEPT", 4)
    monkeypatch.setattr(point_cloud2, "MAX_CLOUD_BYTES_KEPT", 10 * 60)  # ten 60-byte clouds
    scene, clock = FakeScene(), FakeClock()
    values = {"Topic": "/points", "Decay Time": 100.0}
    display = display_class("PointCloud2")("cloud", fake_context(scene, clock=clock), values)
    lookup = lookup_from({"lidar": np.eye(4)})
    for _ in range(3):
        display.receive(three_point_cloud())
        clock.ns += 1_000_000
    status = display.draw(lookup)
    assert status.level.value == "ok" and status.text == "Showing [9] points from [3] messages"
    for _ in range(7):  # between two draws: the bound holds as they arrive
        display.receive(three_point_cloud())
        clock.ns += 1_000_000
    status = display.draw(lookup)
    assert status.level.value == "warn"
    assert status.text.startswith(
        "Showing [12] points from [4] messages; Decay Time keeps at most 4"
    )
    assert len(scene.visible("/displays/cloud")) == 4  # the dropped clouds' nodes are gone
    monkeypatch.setattr(point_cloud2, "MAX_CLOUDS_KEPT", 1000)
    for _ in range(12):
        display.receive(three_point_cloud())
        clock.ns += 1_000_000
    assert display.draw(lookup).text.startswith("Showing [30] points from [10] messages")


def test_point_cloud2_bad_cloud_is_an_error_status_and_config_transformer_kept() -> None:
    scene = FakeScene()
    display = display_class("PointCloud2")("c", fake_context(scene), {"Topic": "/p", "Color Transformer": "Intensity"})  # fmt: skip
    bad = three_point_cloud(frame="map")
    bad.width = 4
    display.receive(bad)
    status = display.draw(lookup_from({"map": np.eye(4)}))
    assert status.level.value == "error" and "Data size (60 bytes)" in status.text
    display.receive(three_point_cloud(frame="map"))
    assert (
        display.draw(lookup_from({"map": np.eye(4)})).text == "Showing [3] points from [1] messages"
    )
    assert display.option("Color Transformer") == "Intensity"  # the config's choice kept


Image = get_message_type("sensor_msgs/msg/Image")
CameraInfo = get_message_type("sensor_msgs/msg/CameraInfo")
OccupancyGrid = get_message_type("nav_msgs/msg/OccupancyGrid")
BOARD = np.indices((4, 4)).sum(axis=0) % 2 == 0


def checkerboard(encoding: str = "rgb8", frame: str = "camera_optical") -> object:
    rgb = np.where(BOARD[..., None], (255, 0, 0), (0, 0, 255)).astype(np.uint8)
    msg = Image(height=4, width=4, encoding=encoding, step=12, data=list(rgb.tobytes()))
    msg.header.frame_id = frame
    return msg


def test_image_display_converts_the_newest_and_reports_bad_encodings() -> None:
    display = display_class("Image")("img", fake_context(FakeScene()), {"Topic": "/camera/image"})
    assert display.draw(lookup_from({})).text == "No messages received"
    display.receive(checkerboard())
    assert display.draw(lookup_from({})).text == "1 images received; showing 4x4"
    assert display.rgb is not None
    np.testing.assert_array_equal(display.rgb[0, 0], (255, 0, 0))
    np.testing.assert_array_equal(display.rgb[0, 1], (0, 0, 255))
    display.receive(checkerboard("rgb16"))
    status = display.draw(lookup_from({}))
    assert status.level.value == "error" and "Unsupported image encoding [rgb16]" in status.text
    specs = display.subscriptions()
    assert [s.type_name for s in specs] == ["sensor_msgs/msg/Image"]
    assert display_class("Camera").ros1_keys["Topic"] == "Image Topic"  # RViz 1's key


def test_camera_display_frustum_from_camera_info_through_tf() -> None:
    scene = FakeScene()
    display = display_class("Camera")("cam", fake_context(scene), {"Topic": "/camera/image_raw"})
    assert [s.topic for s in display.subscriptions()] == ["/camera/image_raw", "/camera/camera_info"]  # fmt: skip
    assert camera_info_topic("/cam/image_raw/compressed") == "/cam/camera_info"
    assert camera_info_topic("image") == "/camera_info"
    display.receive(checkerboard())
    status = display.draw(lookup_from({"camera_optical": shifted(1.0)}))
    assert status.text == "No CameraInfo received on [/camera/camera_info]. Topic may not exist."
    info = CameraInfo(height=4, width=4)
    info.p = [2.0, 0, 2, 0, 0, 2.0, 2, 0, 0, 0, 1, 0]
    display.subscriptions()[1].callback(info)
    status = display.draw(lookup_from({"camera_optical": shifted(1.0)}))
    assert status.level.value == "warn" and "not rendered over the image" in status.text
    (node,) = scene.visible("/displays/cam").values()
    assert node.kind == "camera_frustum" and node.position == (1.0, 0.0, 0.0)
    assert node.kwargs["fov"] == pytest.approx(2 * np.arctan(4 / (2 * 2.0)))
    assert node.kwargs["aspect"] == 1.0
    np.testing.assert_array_equal(node.kwargs["image"], display.rgb)
    status = display.draw(lookup_from({}))
    assert "No transform from [camera_optical] to [map]" in status.text


def occupancy(frame: str = "map") -> object:
    msg = OccupancyGrid()
    msg.header.frame_id = frame
    msg.info.resolution, msg.info.width, msg.info.height = 0.5, 2, 2
    msg.info.origin.position.x = -1.0
    msg.info.origin.orientation.w = 1.0
    msg.data = [0, 100, -1, 50]
    return msg


def test_map_display_texture_placement_and_status() -> None:
    scene = FakeScene()
    display = display_class("Map")("map", fake_context(scene), {"Topic": "/map"})
    assert display.subscriptions()[0].transient_local  # a latched map_server map arrives
    display.receive(occupancy("odom"))
    status = display.draw(lookup_from({}))
    assert status.text == "No transform from [odom] to [map]" and not scene.visible()
    status = display.draw(lookup_from({"odom": shifted(3.0)}))
    assert status.text == "Map OK: 2 X 2 map @ 0.5 m/pix"
    (node,) = scene.visible("/displays/map").values()
    assert node.kind == "image" and node.position == (2.5, 0.5, 0.0)  # 3 - 1 + 0.5, 0.5
    assert (node.kwargs["render_width"], node.kwargs["render_height"]) == (1.0, 1.0)
    image = node.kwargs["image"][::128, ::128]  # cells upscaled to 128 x 128 texels
    np.testing.assert_array_equal(image[0, 0], (255, 255, 255, 178))  # free, first cell
    np.testing.assert_array_equal(image[0, 1], (0, 0, 0, 178))
    bad = occupancy()
    bad.data = [0]
    display.receive(bad)
    status = display.draw(lookup_from({}))
    assert status.level.value == "error" and "data size = 1" in status.text


class _Folder:
    """A viser folder handle as far as the Image display uses it."""

    def __init__(self, label: str, **kwargs: object) -> None:
        self.label, self.removed, self.kwargs = label, False, kwargs
        self.visible = kwargs.get("visible", True)

    def __enter__(self) -> _Folder:
        return self

    def __exit__(self, *_exc: object) -> None:
        return None

    def remove(self) -> None:
        self.removed = True


class _ImageArea:
    """A viser GUI image handle as far as the Image display sets it: the JPEGs it was given.
    With ``gate``, setting an image waits for it (``entered`` says an image is being set)."""

    def __init__(self, gate: threading.Event | None = None) -> None:
        self.jpegs: list[bytes] = []
        self._format = "jpeg"
        self.gate, self.entered = gate, threading.Event()

    @property
    def _data(self) -> bytes:
        return self.jpegs[-1]

    @_data.setter
    def _data(self, value: bytes) -> None:
        self.entered.set()
        if self.gate is not None:
            assert self.gate.wait(scaled(10))
        self.jpegs.append(value)

    @property
    def images(self) -> list[np.ndarray]:
        return [np.asarray(PILImage.open(io.BytesIO(j)).convert("RGB")) for j in self.jpegs]

    @property
    def image(self) -> np.ndarray:
        return self.images[-1]


class _Gui:
    """The parts of viser's GUI API the Image display's image area uses, recorded."""

    def __init__(self) -> None:
        self.folders: list[_Folder] = []
        self.images: list[_ImageArea] = []

    def add_folder(self, label: str, **kwargs: object) -> _Folder:
        self.folders.append(_Folder(label, **kwargs))
        return self.folders[-1]

    def add_image(self, image: np.ndarray, **_kwargs: object) -> _ImageArea:
        self.images.append(_ImageArea())
        return self.images[-1]


def _near(pixel: np.ndarray, rgb: tuple[int, int, int]) -> bool:
    """A JPEG's pixel is the colour within its rounding (a cell's middle keeps its colour)."""
    return int(np.abs(pixel.astype(int) - rgb).max()) <= 12


def test_image_display_shows_each_image_on_arrival_at_the_frame_rate(monkeypatch: pytest.MonkeyPatch) -> None:  # fmt: skip
    """RViz's Image display: its own panel at once (here an image area at the top of the
    control panel, hidden while disabled), and the newest image at each render of its Frame
    Rate: on arrival while the rate allows (jitter-bunched arrivals of a camera at the Frame
    Rate are all shown), else at the next arrival or draw."""
    from robomodel.viewer.displays import image_display

    now = [100.0]
    monkeypatch.setattr(image_display.time, "monotonic", lambda: now[0])
    gui, rate_hz = _Gui(), [30.0]
    context = fake_context(FakeScene())
    context.gui, context.frame_rate_hz = gui, lambda: rate_hz[0]
    display = display_class("Image")("Camera feed", context, {"Topic": "/camera/image"})
    display.build_dock(gui)
    (dock,) = gui.folders
    assert (dock.label, dock.kwargs["order"], dock.kwargs["expand_by_default"], dock.visible) == ("Camera feed", -1000.0, True, True)  # fmt: skip
    (panel,) = gui.images
    display.receive(checkerboard())  # no draw needed: shown when it arrives
    assert display.shown == 1 and display.sender.flush(scaled(10))
    assert panel.image.shape == (320, 320, 3)  # 4x4 with each pixel repeated 80 times
    assert _near(panel.image[40, 40], (255, 0, 0)) and _near(panel.image[40, 120], (0, 0, 255))
    assert display.draw(lookup_from({})).text == "1 images received; showing 4x4"

    def camera(rate: float, seconds: float, jitter_s: float = 0.0) -> int:
        """Images shown of a camera at ``rate`` Hz, every other one ``jitter_s`` late."""
        before, t0 = display.shown, now[0]
        for k in range(round(rate * seconds)):
            now[0] = t0 + (k + 1) / rate + (jitter_s if k % 2 else 0.0)
            display.receive(checkerboard())
        now[0] = t0 + seconds
        return display.shown - before

    assert camera(30.0, 2.0, jitter_s=0.025) == 60  # bunched 8 ms apart, all shown
    # a faster camera: the Frame Rate's 30 a second (and the budget saved before it)
    assert 60 <= camera(90.0, 2.0) <= 60 + image_display.BURST_FRAMES
    rate_hz[0] = 10.0  # Global Options > Frame Rate 10
    assert 30 <= camera(30.0, 3.0) <= 30 + image_display.BURST_FRAMES
    now[0] += 1.0  # the budget saved: BURST_FRAMES images at once
    for _ in range(int(image_display.BURST_FRAMES)):
        display.receive(checkerboard())
    skipped = display.skipped
    display.receive(checkerboard("bgr8"))  # the budget spent: waits
    display.receive(checkerboard("mono8"))  # replaces it: the newest wins
    display.receive(checkerboard("bgr8"))
    assert display.skipped == skipped + 2
    assert display.sender.flush(scaled(10)) and _near(panel.image[40, 40], (255, 0, 0))
    now[0] += 0.11
    display.draw(lookup_from({}))  # the next draw shows the newest
    assert display.sender.flush(scaled(10)) and _near(panel.image[40, 40], (0, 0, 255))
    np.testing.assert_array_equal(display.rgb[0, 0], (0, 0, 255))  # the image shown, as RGB
    display.rename("Front")
    display.set_enabled(False)
    assert (dock.label, dock.visible) == ("Front", False)
    shown = display.shown
    display.receive(checkerboard())
    assert display.shown == shown  # a disabled display shows nothing
    sender = display.sender
    display.close()
    assert dock.removed and display.sender is None
    sent = sender.sent
    sender.submit(PILImage.new("RGB", (4, 4)))  # closed: nothing more reaches the handle
    assert sender.flush(scaled(10)) and sender.sent == sent


def _solid(rgb: tuple[int, int, int]) -> PILImage.Image:
    return PILImage.new("RGB", (16, 16), rgb)


def test_image_sender_keeps_only_the_newest_image_waiting() -> None:
    """While one image is being encoded and set, those handed over meanwhile replace each
    other: the page gets the newest next, never a queue of older ones."""
    gate = threading.Event()
    area = _ImageArea(gate)
    sender = LatestImageSender(area, name="test")
    sender.submit(_solid((255, 0, 0)))
    assert area.entered.wait(scaled(10))  # red is being set; the sender waits for the page
    for colour in ((0, 255, 0), (0, 0, 255), (255, 255, 255)):
        sender.submit(_solid(colour))
    assert sender.replaced == 2 and not sender.flush(0.0)
    gate.set()
    assert sender.flush(scaled(10))
    assert [_near(image[8, 8], c) for image, c in zip(area.images, ((255, 0, 0), (255, 255, 255)), strict=True)] == [True, True]  # fmt: skip
    assert sender.sent == 2
    gate.clear()
    area.entered.clear()
    sender.submit(_solid((0, 255, 0)))
    assert area.entered.wait(scaled(10))
    sender.submit(_solid((0, 0, 255)))
    sender.discard()  # a topic change: the one waiting is not sent
    gate.set()
    assert sender.flush(scaled(10)) and sender.sent == 3 and _near(area.image[8, 8], (0, 255, 0))
    sender.close()
    sender.submit(_solid((0, 0, 255)))  # closed: ignored
    assert sender.flush(scaled(10)) and sender.sent == 3


def test_image_sender_thread_ends_when_idle_and_restarts(monkeypatch: pytest.MonkeyPatch) -> None:
    """No thread is left waiting for a camera that stopped: it ends when idle, and the next
    image starts another."""
    from robomodel.viewer.displays import image_sender

    monkeypatch.setattr(image_sender, "IDLE_EXIT_S", 0.05)
    area = _ImageArea()
    sender = LatestImageSender(area, name="idle")
    assert not sender.running
    sender.submit(_solid((255, 0, 0)))
    assert sender.flush(scaled(10))
    wait_until(lambda: not sender.running, scaled(10), what="the idle thread to end")
    sender.submit(_solid((0, 0, 255)))
    assert sender.flush(scaled(10)) and sender.sent == 2 and _near(area.image[8, 8], (0, 0, 255))
    sender.close()
