"""Helpers shared by the benchmarks: robust timing and the example-robot-data location."""

from __future__ import annotations

import statistics
import sysconfig
import time
from collections.abc import Callable
from pathlib import Path


def example_robot_data(relative: str) -> Path:
    prefix = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix"
    return prefix / "share" / "example-robot-data" / "robots" / relative


def ros1_env(work: Path, port: int | str) -> dict[str, str]:
    """The environment of Debian's ROS 1 processes: only ``/usr`` on the path, a master on
    ``port``, ROS's home and logs under ``work`` (nothing of this venv, nothing of ``~``)."""
    return {
        "PATH": "/usr/bin:/bin",
        "HOME": str(work),
        "ROS_HOME": str(work / ".ros"),
        "ROS_MASTER_URI": f"http://localhost:{port}",
        "ROS_PACKAGE_PATH": "/usr/share",
        "LANG": "C.UTF-8",
    }


def paced_sends(seconds: float, rate_hz: float, send: Callable[[int], None]) -> tuple[int, float]:
    """Call ``send(k)`` for k = 0, 1, ... on the schedule ``start + k / rate_hz`` for
    ``seconds`` (never accumulated: a late send is made at once, not skipped); returns
    (messages sent, elapsed [s]). Standard library only: Debian's Python runs it too
    (``_ros1_rsp.py``)."""
    period = 1.0 / rate_hz
    start = time.perf_counter()
    sent = 0
    while True:
        now = time.perf_counter()
        if now - start >= seconds:
            break
        target = start + sent * period
        if now < target:
            time.sleep(max(0.0, target - now - 0.0001))
            continue
        send(sent)
        sent += 1
    return sent, time.perf_counter() - start


def time_call(func: Callable[[], object], *, repeat: int = 7, min_time_s: float = 0.2) -> float:
    """Median over ``repeat`` rounds of the mean time per call [s]; each round >= min_time_s."""
    func()
    number = 1
    while True:
        start = time.perf_counter()
        for _ in range(number):
            func()
        elapsed = time.perf_counter() - start
        if elapsed >= min_time_s / 4:
            break
        number *= 2
    rounds = []
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in range(number):
            func()
        rounds.append((time.perf_counter() - start) / number)
    return statistics.median(rounds)


def time_interleaved(
    ours: Callable[[], object],
    reference: Callable[[], object],
    *,
    rounds: int = 21,
    min_time_s: float = 0.02,
) -> tuple[float, float, float]:
    """Median time per call [s] of ``ours`` and ``reference`` and the median per-round ratio.

    The two run alternately (ours, reference, ours, ...), each round long enough to time, so
    that load from other jobs on the machine affects both alike.
    """
    numbers = []
    for func in (ours, reference):
        func()
        number = 1
        while True:
            start = time.perf_counter()
            for _ in range(number):
                func()
            if time.perf_counter() - start >= min_time_s:
                break
            number *= 2
        numbers.append(number)
    t_ours, t_ref, ratios = [], [], []
    for _ in range(rounds):
        times = []
        for func, number in zip((ours, reference), numbers, strict=True):
            start = time.perf_counter()
            for _ in range(number):
                func()
            times.append((time.perf_counter() - start) / number)
        t_ours.append(times[0])
        t_ref.append(times[1])
        ratios.append(times[0] / times[1])
    return statistics.median(t_ours), statistics.median(t_ref), statistics.median(ratios)


def synthetic_chain_urdf(n_links: int) -> str:
    """A serial chain of ``n_links`` links (revolute joints about z, y, x in turn), each with
    an inertial, a box visual and a cylinder collision: the scaling benchmarks' robot."""
    parts = ['<?xml version="1.0"?>', f'<robot name="chain{n_links}">']
    for i in range(n_links):
        parts.append(
            f'  <link name="link_{i}">\n'
            '    <inertial><origin xyz="0 0 0.05"/><mass value="1.0"/>'
            '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>\n'
            '    <visual><origin xyz="0 0 0.05" rpy="0 0 0"/>'
            '<geometry><box size="0.04 0.04 0.1"/></geometry></visual>\n'
            '    <collision><origin xyz="0 0 0.05"/>'
            '<geometry><cylinder radius="0.02" length="0.1"/></geometry></collision>\n'
            "  </link>"
        )
        if i:
            axis = ("0 0 1", "0 1 0", "1 0 0")[i % 3]
            parts.append(
                f'  <joint name="joint_{i}" type="revolute">'
                f'<parent link="link_{i - 1}"/><child link="link_{i}"/>'
                f'<origin xyz="0 0 0.1" rpy="0.01 0 0.02"/><axis xyz="{axis}"/>'
                '<limit lower="-3.14" upper="3.14" effort="10" velocity="1"/></joint>'
            )
    parts.append("</robot>\n")
    return "\n".join(parts)
