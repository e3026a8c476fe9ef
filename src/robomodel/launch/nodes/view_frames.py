"""``view_frames`` as a node: listen to /tf and /tf_static, then draw the tree with Graphviz.

Seed 000's "Tree of tf: ``roslaunch tf view_frames``" is ``rosrun tf view_frames``, here
``robomodel run tf view_frames``. Three scripts, each transcribed for its printed lines and the
files it writes into the current folder:

- ROS 1 ``tf view_frames`` (Debian's tf-tools 1.13.2, /usr/lib/tf/view_frames): ``Listening
  to /tf for 5.0 seconds``, ``Done Listening``, ``frames.gv`` in tf's ``allFramesAsDot`` form,
  then ``dot -V``'s line, ``Detected dot version X`` and ``frames.pdf generated``. Debian's
  script ends there in a TypeError under Python 3 (it matches a text pattern against dot's
  bytes) and writes no pdf; robomodel writes it. (``--node`` polls a node's ``tf_frames``
  service, which no robomodel node offers: one line says so.)
- ROS 1 ``tf2_tools view_frames.py``: ``frames.gv`` and ``frames.pdf``.
- ROS 2 ``tf2_tools view_frames`` (ros2/geometry2, tf2_tools/view_frames.py): ``-t/--wait-time``
  (5 s), ``-o/--output`` (``OUT.gv`` and ``OUT.pdf``, else ``frames_<date_time>``).

tf2_tools' graph is ``generate_dot`` (:func:`robomodel.tf.frames_dot`). The broadcaster is
robomodel's listener's ``default_authority`` (ROS 1's names the publishing node). The listening
time counts once the node's session has linked up with the others, as ``robomodel frames
--live`` does.
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from robomodel.errors import RobomodelError
from robomodel.launch.nodes.base import NodeContext, RunningNode, ThreadNode, register

__all__: list[str] = []


@dataclass(frozen=True)
class _Plan:
    """What one view_frames run does: how long it listens, which files it writes, its words."""

    wait_s: float
    gv_path: Path
    pdf_path: Path
    script: str  # "tf", "tf2_tools ros1" or "tf2_tools ros2": whose lines are printed


def _plan(ctx: NodeContext) -> _Plan:
    """The script's command line (ROS arguments already taken out)."""
    words = [a for a in ctx.spec.args if ":=" not in a]
    if ctx.spec.dialect == "ros2":
        parser = argparse.ArgumentParser(prog="view_frames", add_help=False, exit_on_error=False)
        parser.add_argument("--wait-time", "-t", type=float, default=5.0)
        parser.add_argument("--output", "-o")
        try:
            parsed, extra = parser.parse_known_args(words)
        except argparse.ArgumentError as exc:
            raise RobomodelError(f"view_frames: {exc}") from None
        if extra:
            raise RobomodelError(
                f"view_frames: unrecognized arguments: {' '.join(extra)} (it takes -t SECONDS "
                "and -o NAME)"
            )
        stem = parsed.output or f"frames_{time.strftime('%Y-%m-%d_%H.%M.%S')}"
        return _Plan(parsed.wait_time, Path(f"{stem}.gv"), Path(f"{stem}.pdf"), "tf2_tools ros2")
    if "--node" in words or any(w.startswith("--node=") for w in words):
        raise RobomodelError(
            "view_frames: --node polls a node's tf_frames service, which robomodel's nodes do "
            "not offer; run view_frames without --node to listen to /tf"
        )
    if words:
        raise RobomodelError(f"view_frames: unrecognized arguments: {' '.join(words)}")
    script = "tf" if ctx.spec.package == "tf" else "tf2_tools ros1"
    return _Plan(5.0, Path("frames.gv"), Path("frames.pdf"), script)


def _dot_version(dot: str) -> str:
    """``dot -V``'s line (Graphviz prints it on stderr), and tf's "Detected" line."""
    line = subprocess.run([dot, "-V"], capture_output=True, text=True).stderr.strip()
    found = re.search(r".*version (\d+\.?\d*)", line)  # tf's pattern
    detected = (
        f"Detected dot version {found.group(1)}"
        if found
        else "Warning: failed to determine your version of dot.  Assuming v2.16"
    )
    return f"{line}\n{detected}"


def _write(plan: _Plan, text: str) -> int:
    """frames.gv, then the pdf through ``dot -Tpdf``, with the script's lines."""
    from robomodel._atomic import atomic_write_text
    from robomodel.cli.graph import render_dot

    atomic_write_text(plan.gv_path, text)
    dot = shutil.which("dot")
    if dot is None:
        print(
            "Warning: Could not execute `dot -V`.  Is graphviz installed?", file=sys.stderr,
            flush=True,
        )  # fmt: skip
        return 255 if plan.script == "tf" else 1  # tf's sys.exit(-1)
    if plan.script == "tf":
        print(_dot_version(dot), flush=True)
    render_dot(text, plan.pdf_path)
    if plan.script == "tf":
        print(f"{plan.pdf_path} generated", flush=True)
    return 0


def _view_frames(ctx: NodeContext) -> RunningNode:
    from robomodel.runtime.tf_listener import TransformListener
    from robomodel.tf.view_frames import frames_dot, tf_frames_dot

    plan = _plan(ctx)
    node = ctx.runtime.create_node(
        ctx.spec.name or "view_frames", ctx.namespace, remappings=ctx.remappings
    )
    buffer = TransformListener(node).buffer

    def work(thread: ThreadNode) -> int:
        from robomodel.cli._bus import wait_for_peers

        try:
            wait_for_peers(ctx.runtime, timeout_s=5.0)
            if plan.script == "tf":
                print(f"Listening to /tf for {plan.wait_s} seconds", flush=True)
            else:
                print(f"Listening to tf data for {plan.wait_s} seconds...", flush=True)
            if thread.stopping.wait(plan.wait_s):
                return 0  # Ctrl-C while listening: nothing is written
            if plan.script == "tf":
                print("Done Listening", flush=True)
            else:
                print(f"Generating graph in {plan.pdf_path} file...", flush=True)
            if plan.script == "tf":
                return _write(plan, tf_frames_dot(buffer, current_time_s=time.time()))
            return _write(plan, frames_dot(buffer, recorded_time_s=time.time()))
        finally:
            node.destroy()

    return ThreadNode(f"view_frames {ctx.spec.fqn}", work, ctx.log)


_PURPOSE = "listens to /tf for 5 s, writes frames.gv and frames.pdf (view_frames)"
register("ros1", "tf", "view_frames", purpose=_PURPOSE)(_view_frames)
register("ros1", "tf2_tools", "view_frames.py", purpose=_PURPOSE)(_view_frames)
register(
    "ros2", "tf2_tools", "view_frames",
    purpose="listens to tf for -t seconds (5), writes frames_<time>.gv/.pdf or -o NAME.gv/.pdf",
)(_view_frames)  # fmt: skip
