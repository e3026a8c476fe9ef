"""Time from starting a launch file to the first /tf message: robomodel launch vs roslaunch.

The launch file is the display launch of seed 000 without RViz (the description as a
``textfile`` parameter, joint_state_publisher, robot_state_publisher), so that Debian's
roslaunch, whose RViz is not installable here, runs the same nodes. For roslaunch a roscore is
already running (as in the lessons: ``roscore`` in its own terminal); robomodel needs none.

Each round first starts a listener (``rostopic echo -n 1 /tf`` or ``robomodel topic echo /tf
--once``) and waits until it is up, then starts the launch and measures the wall time until the
listener has printed its message. The two run alternately, round by round.

    python bench/bench_launch.py --rounds 7
"""

from __future__ import annotations

import argparse
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import ros1_env

ROOT = Path(__file__).resolve().parents[1]
URDF = ROOT / "examples" / "gripper_description" / "urdf" / "planar_3dof.urdf"
LAUNCH = f"""<launch>
  <param name="robot_description" textfile="{URDF}"/>
  <node name="joint_state_publisher" pkg="joint_state_publisher" type="joint_state_publisher"/>
  <node name="robot_state_publisher" pkg="robot_state_publisher" type="robot_state_publisher"/>
</launch>
"""
ROBOMODEL = [sys.executable, "-m", "robomodel.cli.main"]
_LISTENER_HEAD_START_S = 3.0


def _stop(proc: subprocess.Popen[bytes]) -> None:
    try:
        os.killpg(proc.pid, signal.SIGINT)
        proc.wait(20)
    except (subprocess.TimeoutExpired, ProcessLookupError):
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()


def _first_tf(listener: list[str], launch: list[str], env: dict[str, str]) -> float:
    echo = subprocess.Popen(
        listener, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, env=env,
        start_new_session=True,
    )  # fmt: skip
    time.sleep(_LISTENER_HEAD_START_S)
    start = time.perf_counter()
    proc = subprocess.Popen(
        launch, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env,
        start_new_session=True,
    )  # fmt: skip
    try:
        echo.wait(60)
        elapsed = time.perf_counter() - start
        assert echo.stdout is not None
        if b"transforms" not in echo.stdout.read():
            raise RuntimeError(f"{listener[0]} got no /tf")
        return elapsed
    finally:
        _stop(proc)
        if echo.poll() is None:
            _stop(echo)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--rounds", type=int, default=7)
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp(prefix="bench_launch_"))
    launch = work / "display_no_rviz.launch"
    launch.write_text(LAUNCH)
    port = "11377"
    ros_env = ros1_env(work, port)
    our_env = {**os.environ}
    core = subprocess.Popen(
        ["/usr/bin/roscore", "-p", port], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        env=ros_env, start_new_session=True,
    )  # fmt: skip
    time.sleep(4)
    ours, reference = [], []
    try:
        for k in range(args.rounds):
            domain = str(200 + k % 20)
            ours.append(
                _first_tf(
                    [*ROBOMODEL, "topic", "echo", "/tf", "--once", "--domain-id", domain],
                    [*ROBOMODEL, "launch", str(launch), "--headless", "--domain-id", domain],
                    our_env,
                )
            )
            reference.append(
                _first_tf(
                    ["/usr/bin/rostopic", "echo", "-n", "1", "/tf"],
                    ["/usr/bin/roslaunch", str(launch)],
                    ros_env,
                )
            )
            print(f"round {k + 1}: robomodel {ours[-1]:.3f} s, roslaunch {reference[-1]:.3f} s")
    finally:
        _stop(core)
        shutil.rmtree(work, ignore_errors=True)  # the launch file, roscore's logs, ROS_HOME
    ratio = statistics.median(o / r for o, r in zip(ours, reference, strict=True))
    print(
        f"time to the first /tf: robomodel launch {statistics.median(ours):.3f} s, "
        f"roslaunch (roscore running) {statistics.median(reference):.3f} s, "
        f"ratio {ratio:.2f} (median of {args.rounds} interleaved rounds)"
    )


if __name__ == "__main__":
    main()
