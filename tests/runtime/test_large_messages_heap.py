"""A process that opens a bus between processes (Zenoh, ROS 1), or runs a Foxglove bridge,
takes its large message buffers from glibc's heap: allocating and freeing image-sized buffers costs no page faults,
where glibc's defaults map or trim them afresh each time (``robomodel._heap``)."""

from __future__ import annotations

import platform
import subprocess
import sys
import textwrap

import pytest

from tests.conftest import unique_domain
from tests.ros1wire.conftest import free_port
from tests.timing import scaled

FAULTS = textwrap.dedent(
    """
    import resource, sys
    from robomodel.runtime import Context
    bus = sys.argv[1]
    if bus == "ros1":
        from robomodel.runtime.transport.ros1.master import Master
        master = Master(f"http://127.0.0.1:{sys.argv[2]}/", "127.0.0.1")
        context = Context("ros1", master=f"http://127.0.0.1:{sys.argv[2]}/")
    elif bus == "zenoh":
        context = Context("zenoh", domain_id=int(sys.argv[2]))
    else:
        context = Context()
    if bus == "bridge":  # foxglove_bridge on the in-process bus: the SDK's frames
        from robomodel.bridges.foxglove_bridge import FoxgloveBridge
        from robomodel.bridges.rosapi import Ros1Params
        from robomodel.description.packages import PackageIndex
        from robomodel.launch.param_server import ParamServer
        bridge = FoxgloveBridge(context, Ros1Params(ParamServer()), dialect="ros2",
                                package_index=PackageIndex(), port=0, log=lambda line: None)
    size = 640 * 480 * 3  # a 640x480 rgb8 image

    def pair():  # its CDR and the transport's copy of it
        payload, copy = bytearray(size), bytearray(size)
        del payload, copy

    pair()
    before = resource.getrusage(resource.RUSAGE_THREAD).ru_minflt
    for _ in range(20):
        pair()
    print(resource.getrusage(resource.RUSAGE_THREAD).ru_minflt - before)
    if bus == "bridge":
        bridge.stop()
    context.shutdown()
    """
)


def _faults(bus: str, arg: str) -> int:
    done = subprocess.run([sys.executable, "-c", FAULTS, bus, arg], capture_output=True,
                          text=True, timeout=scaled(60))  # fmt: skip
    assert done.returncode == 0, done.stderr
    return int(done.stdout.split()[-1])


@pytest.mark.skipif(platform.libc_ver()[0] != "glibc", reason="glibc's malloc settings")
@pytest.mark.parametrize("bus", ["zenoh", "ros1", "bridge"])
def test_image_sized_buffers_reuse_the_heap(bus: str) -> None:
    """On the Zenoh and ROS 1 buses, and in a process with a Foxglove bridge whatever its bus."""
    arg = {"zenoh": unique_domain, "ros1": lambda: str(free_port())}.get(bus, str)()
    assert _faults(bus, arg) < 20
    # the same process on the in-process bus keeps glibc's defaults: ~450 faults a pair
    assert _faults("inproc", "") > 20 * 100
