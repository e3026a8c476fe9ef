"""The plot and the topic publisher take any type the graph shows, through the page (headless
Chromium), on the Zenoh and the ROS 1 bus: ``sensor_msgs/msg/Image`` (robomodel has no class
of its own for it: built from rosbags' store) and ``my_msgs/msg/Reading`` of a test interface
package (built from its ``.msg`` file)."""

from __future__ import annotations

import itertools
import os
import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from robomodel.runtime.msg import _resolver, get_message_type
from robomodel.runtime.node import Node
from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from tests.conftest import EXAMPLES, ROBOMODEL, end_process, free_port, unique_domain
from tests.viewer.conftest import gui_row, new_page, open_viewer, save_shot, type_into, wait_for
from tests.viewer.test_tools_inprocess import on_loop

pytestmark = pytest.mark.browser
pytest.importorskip("viser")


def _package(root: Path) -> Path:
    package = root / "my_msgs"
    (package / "msg").mkdir(parents=True)
    (package / "package.xml").write_text(
        '<package format="3"><name>my_msgs</name><version>0.0.0</version></package>'
    )
    (package / "msg" / "Reading.msg").write_text("float64 value\nint16[3] raw\n")
    return root


def _answers(uri: str) -> bool:
    import xmlrpc.client

    try:
        return int(xmlrpc.client.ServerProxy(uri).getPid("/test")[0]) == 1
    except OSError:
        return False


# the ROS 1 viewer and its page serve two tests: one worker for both
_ON_ROS1 = pytest.mark.xdist_group("tools_any_type_browser_ros1")
_ROS1 = pytest.param("ros1", marks=_ON_ROS1)


@pytest.fixture(scope="module", params=["zenoh", _ROS1])
def viewer(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Iterator[Viewer]:  # fmt: skip
    _resolver.configure(package_paths=(_package(tmp_path_factory.mktemp("ws")),))
    master: subprocess.Popen[str] | None = None
    bus: dict[str, Any] = {"bus": request.param}
    if request.param == "zenoh":
        bus["domain_id"] = int(unique_domain())
    else:
        port = free_port()
        env = {k: v for k, v in os.environ.items() if not k.startswith("ROS")}
        master = subprocess.Popen(
            [*ROBOMODEL, "master", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL, text=True, start_new_session=True,
        )  # fmt: skip
        bus["master"] = f"http://127.0.0.1:{port}/"
        wait_for(lambda: _answers(bus["master"]), timeout_s=30, what="the ROS 1 master")
    source = RobotSource(str(EXAMPLES / "simplebot_description/urdf/simplebot.urdf.xacro"))
    viewer = Viewer(ViewerOptions(sources=(source,), port=0, **bus))
    try:
        viewer.start()
        yield viewer
    finally:
        viewer.close()
        _resolver.configure(package_paths=())
        if master is not None:
            end_process(master, group=True)


@pytest.fixture(scope="module")
def shared_page(browser: Any, viewer: Viewer) -> Iterator[Any]:
    """One page per bus's viewer for the tests on it: a page's first frames (software WebGL
    compiling its shaders, the scene's first load) cost more CPU than a test's own work."""
    with new_page(browser) as page:
        open_viewer(page, viewer.url)
        yield page


@pytest.fixture
def page(shared_page: Any, viewer: Viewer) -> Iterator[Any]:
    """The bus's page; the plot's series are cleared after each test (rqt_plot's Clear)."""
    yield shared_page
    on_loop(viewer, viewer.tools.plot.clear)


def _open(page: Any, folder: str, row: str) -> None:
    """Open ``folder`` unless its control ``row`` shows already (a click would close it)."""
    if not gui_row(page, row).filter(visible=True).count():
        page.get_by_text(folder, exact=True).click()


def test_plot_and_publisher_take_types_built_from_definitions(viewer: Viewer, page: Any) -> None:
    assert viewer.context is not None
    context = viewer.context
    image, reading = (get_message_type(n) for n in ("sensor_msgs/Image", "my_msgs/msg/Reading"))
    assert not image.__module__.endswith(".sensor_msgs")  # no class of robomodel's own
    received: list[Any] = []

    def make_node() -> Node:
        node = context.create_node("sensors")
        pubs = (
            node.create_publisher(image, "/cam", 10),
            node.create_publisher(reading, "/reading", 10),
        )
        count = [0]

        def tick() -> None:
            count[0] += 1
            pubs[0].publish(image(height=1, width=2, encoding="mono8", step=2,
                                  data=[count[0] % 200, 7]))  # fmt: skip
            pubs[1].publish(reading(value=0.5 * count[0], raw=[1, -count[0], 3]))

        node.create_timer(0.05, tick)
        node.create_subscription(reading, "/out", received.append, 10)
        return node

    on_loop(viewer, make_node)
    wait_for(
        lambda: {"/cam", "/reading"} <= set(viewer.tools.tools.topic_types()),
        timeout_s=30,
        what="both topics in the graph, with their types",
    )
    _open(page, "Plot", "Field")
    for path in ("/reading/raw[1]", "/cam/data[0]"):
        type_into(page, "Field", path, viewer.server)
        page.get_by_text("Add series", exact=True).click()
        page.get_by_text(path).first.wait_for()
    plot = viewer.tools.plot
    wait_for(lambda: len(plot.data.series) == 2 and all(len(s.values) > 5 for s in plot.data.series),
             what="samples of both series")  # fmt: skip
    raw, data = plot.data.series
    assert all(v < 0 for v in raw.values) and all(0 <= v < 200 for v in data.values)
    page.locator(".uplot canvas").first.wait_for()
    # The publisher: a field of the package's type, from an expression.
    _open(page, "Topic Publisher", "Pub topic")
    type_into(page, "Pub topic", "/out", viewer.server)
    type_into(page, "Pub type", "my_msgs/msg/Reading", viewer.server)
    type_into(page, "Pub field", "raw[2]", viewer.server)
    type_into(page, "Expression", "i * 2", viewer.server)
    type_into(page, "Variables", "", viewer.server)
    gui_row(page, "Publishing").locator("input[type=checkbox]").first.click()
    wait_for(lambda: len(received) >= 3, timeout_s=30, what="the page's publications")
    values = [list(m.raw) for m in received[:3]]  # i = 0, 1, 2, ... (ROS 1 may miss the first)
    assert all(v[:2] == [0, 0] for v in values)
    assert [b[2] - a[2] for a, b in itertools.pairwise(values)] == [2, 2]
    assert type(received[0]).__typename__ == "my_msgs/msg/Reading"
    page.get_by_text("publishing my_msgs/msg/Reading").first.wait_for()
    save_shot(page, f"tools_any_type_{viewer.options.bus}")


# A type no package or store has: only its (Debian rospy) publisher knows it, and sends its
# definition in the TCPROS header (as in tests/ros1wire/test_types_from_definitions_ros1.py).
_UNKNOWN = r"""
import genpy.dynamic, rospy
rospy.init_node("debian_unknown", anonymous=True)
text = "geometry_msgs/Point where\nuint8 level\n" + "=" * 80
text += "\nMSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n"
Sample = genpy.dynamic.generate_dynamic("plot_msgs/Sample", text)["plot_msgs/Sample"]
Point = genpy.dynamic.generate_dynamic("geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n")
pub = rospy.Publisher("/sample", Sample, queue_size=1)
while not rospy.is_shutdown():
    pub.publish(Sample(where=Point["geometry_msgs/Point"](1.0, -2.0, 0.5), level=7))
    rospy.sleep(0.1)
"""


@_ON_ROS1
@pytest.mark.parametrize("viewer", ["ros1"], indirect=True)
def test_plot_takes_a_type_only_its_ros1_publisher_knows(
    viewer: Viewer, page: Any, tmp_path: Path
) -> None:
    """The viewer learns plot_msgs/Sample from the publisher's definition, as topic echo does."""
    if not Path("/usr/lib/python3/dist-packages/genpy").is_dir():
        pytest.skip("Debian's python3-genpy is not installed (tools/system-deps test)")
    script = tmp_path / "unknown.py"
    script.write_text(_UNKNOWN)
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS") and k != "PYTHONPATH"}
    env |= {"ROS_MASTER_URI": str(viewer.options.master), "ROS_IP": "127.0.0.1",
            "ROS_HOME": str(tmp_path / ".ros")}  # fmt: skip
    debian = subprocess.Popen(["/usr/bin/python3", str(script)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)  # fmt: skip
    try:
        tools = viewer.tools.tools
        wait_for(lambda: "/sample" in tools.topic_types(), timeout_s=60,
                 what="plot_msgs/Sample learned from its publisher")  # fmt: skip
        _open(page, "Plot", "Field")
        type_into(page, "Field", "/sample/where/y", viewer.server)
        page.get_by_text("Add series", exact=True).click()
        page.get_by_text("/sample/where/y").first.wait_for()
        series = viewer.tools.plot.data.series
        wait_for(lambda: series and len(series[0].values) > 3, what="samples of /sample/where/y")
        assert set(series[0].values) == {-2.0}
    finally:
        debian.kill()
        debian.wait()
