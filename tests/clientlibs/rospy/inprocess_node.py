"""A rospy node of the test's own process on a ROS 1 master of its own, set up as
``rospy.init_node`` sets up a node, for the in-process rospy tests."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from robomodel.clientlibs.rospy import core, dispatch
from robomodel.clientlibs.rospy.topics import _SubscriberImpl
from robomodel.runtime.context import Context
from robomodel.runtime.msg import _resolver
from robomodel.runtime.transport.ros1.master import Master
from tests.ros1wire.conftest import free_port
from tests.timing import scaled


@contextmanager
def rospy_node(name: str, package_paths: tuple[Path, ...] = ()) -> Iterator[str]:
    """The node ``name`` (``/name``) on a new master, its spinning thread started, with
    ``package_paths`` on the type resolver's path; yields the master's URI. Afterwards the
    node, its subscribers' threads and the master are gone and the path is empty again."""
    if package_paths:
        _resolver.configure(package_paths=package_paths)
    uri = f"http://127.0.0.1:{free_port()}/"
    master = Master(uri, "127.0.0.1")
    context = Context("ros1", master=uri)
    ros_node = context.create_node(name.lstrip("/"), enable_rosout=False)
    core.set_state(core.NodeState(f"/{name.lstrip('/')}", {}, context, ros_node))
    spinner = threading.Thread(target=context.spin, daemon=True)  # as init_node starts it
    spinner.start()
    try:
        yield uri
    finally:
        core._LIFE.state = None
        context.shutdown()
        spinner.join(scaled(5))
        _SubscriberImpl.forget_all()
        dispatch.close_all()
        master.close()
        if package_paths:
            _resolver.configure(package_paths=())
