"""A viewer beside a publisher process: the browser tests of displays feed the viewer from
another process on the Zenoh bus, as a robot or a bag replay would."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

from tests.conftest import end_process, unique_domain

if TYPE_CHECKING:
    from robomodel.viewer import Viewer

__all__ = ["EMPTY_ROBOT", "publish_stamped_until_stopped", "publish_until_stopped", "viewer_fed_by"]

ROOT = Path(__file__).resolve().parents[2]
EMPTY_ROBOT = '<?xml version="1.0"?><robot name="frame_only"><link name="map"/></robot>\n'


@contextlib.contextmanager
def viewer_fed_by(module: str, tmp_path: Path, *args: str) -> Iterator[Viewer]:
    """A viewer (fixed frame ``map``, no tools) of a description that draws nothing, on a
    domain of its own, and ``python -m <module> <domain> <args>`` publishing there (it prints
    "publishing" once ready; it is stopped with SIGINT at the end)."""
    from robomodel.viewer import RobotSource, Viewer, ViewerOptions

    domain = unique_domain()
    urdf = tmp_path / "frame_only.urdf"  # the viewer needs a description; this one draws nothing
    urdf.write_text(EMPTY_ROBOT)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT / "src"), str(ROOT)]))
    publisher = subprocess.Popen(
        [sys.executable, "-m", module, domain, *args],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT, env=env,
    )  # fmt: skip
    try:
        assert publisher.stdout is not None
        assert "publishing" in publisher.stdout.readline()
        viewer = Viewer(ViewerOptions(sources=(RobotSource(str(urdf)),), port=0, bus="zenoh",
                                      domain_id=int(domain), fixed_frame="map", tools=False))  # fmt: skip
        viewer.start()
        try:
            yield viewer
        finally:
            viewer.close()
    finally:
        end_process(publisher)


def publish_until_stopped(context: Any, node: Any, publish: Callable[[], None]) -> None:
    """The publisher process's side: ``publish()`` every 0.25 s on ``node`` until SIGINT or
    SIGTERM, after saying "publishing" on stdout; the context is shut down at the end."""
    node.create_timer(0.25, publish)
    signal.signal(signal.SIGTERM, signal.default_int_handler)  # stop as on Ctrl-C
    print("publishing", flush=True)
    try:
        context.spin()
    except KeyboardInterrupt:
        pass
    finally:
        context.shutdown()


def publish_stamped_until_stopped(
    context: Any, node: Any, pubs: dict[str, Any], transform: Any, messages: dict[str, Any]
) -> None:
    """:func:`publish_until_stopped` of ``transform`` on ``pubs["/tf"]``, stamped now each
    time, and of each of ``messages`` on its topic's publisher."""
    from robomodel.runtime.msg import TFMessage

    def publish() -> None:
        now = node.get_clock().now_ns()
        transform.header.stamp.sec, transform.header.stamp.nanosec = divmod(now, 1_000_000_000)
        pubs["/tf"].publish(TFMessage(transforms=[transform]))
        for topic, msg in messages.items():
            pubs[topic].publish(msg)

    publish_until_stopped(context, node, publish)
