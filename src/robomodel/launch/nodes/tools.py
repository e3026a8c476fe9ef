"""Command-line tools that run as nodes: ``tf tf_echo`` / ``tf2_ros tf2_echo`` and ``xacro``.

``tf_echo SOURCE TARGET [RATE]`` (ROS 1's tf) and ``tf2_echo SOURCE TARGET [RATE]`` (tf2_ros)
print the pose of TARGET in SOURCE once a second (RATE in Hz), in tf2_echo's format
(:func:`robomodel.tf.format_echo`), waiting with tf2_echo's message while it is not known.
``xacro FILE [name:=value ...] [-o OUT]`` prints (or writes) the expansion and ends, as the
``xacro`` executable does.
"""

from __future__ import annotations

import sys
import time

from robomodel.errors import RobomodelError
from robomodel.launch.nodes.base import NodeContext, RunningNode, ThreadNode, register

__all__: list[str] = []


def _echo_args(ctx: NodeContext) -> tuple[str, str, float]:
    words = [a for a in ctx.spec.args if ":=" not in a]
    if len(words) not in (2, 3):
        raise RobomodelError(
            f"{ctx.spec.executable}: usage: {ctx.spec.executable} SOURCE_FRAME TARGET_FRAME "
            "[echo_rate]"
        )
    rate_hz = 1.0
    if len(words) == 3:
        try:
            rate_hz = float(words[2])
        except ValueError:
            rate_hz = 0.0
        if not rate_hz > 0:
            raise RobomodelError(
                f"{ctx.spec.executable}: Failed to convert rate argument '{words[2]}' to a "
                "positive rate"
            )
    return words[0], words[1], rate_hz


def _echo(ctx: NodeContext) -> RunningNode:
    from robomodel.runtime.tf_listener import TransformListener
    from robomodel.tf import TransformError, format_echo

    source, target, rate_hz = _echo_args(ctx)
    node = ctx.runtime.create_node(
        ctx.spec.name or ctx.spec.executable, ctx.namespace, remappings=ctx.remappings
    )
    buffer = TransformListener(node).buffer

    def work(thread: ThreadNode) -> int:
        last_wait = -1.0
        try:
            while not thread.stopping.is_set():
                try:
                    transform = buffer.lookup_transform(source, target)
                except TransformError as exc:
                    if time.monotonic() - last_wait >= 1.0:  # tf2_echo says it once a second
                        print(f"Waiting for transform {source} ->  {target}: {exc}",
                              file=sys.stderr, flush=True)  # fmt: skip
                        last_wait = time.monotonic()
                    thread.stopping.wait(0.1)
                    continue
                sys.stdout.write(format_echo(transform))
                sys.stdout.flush()
                thread.stopping.wait(1.0 / rate_hz)
        finally:
            node.destroy()
        return 0

    return ThreadNode(f"{ctx.spec.executable} {ctx.spec.fqn}", work, ctx.log)


register("ros1", "tf", "tf_echo", purpose="prints the pose of TARGET in SOURCE (tf_echo)")(_echo)
register("ros1", "tf2_ros", "tf2_echo", purpose="prints the pose of TARGET in SOURCE")(_echo)
register("ros2", "tf2_ros", "tf2_echo", purpose="prints the pose of TARGET in SOURCE")(_echo)


def _xacro(ctx: NodeContext) -> RunningNode:
    from robomodel._atomic import atomic_write_text
    from robomodel.xacro import expand

    inputs, output, mappings = _xacro_args(ctx.spec.args)
    # a ROS 1 command line's name:=value words are its remaps (rosgraph's mappings)
    mappings = {**dict(ctx.spec.remaps), **mappings}
    index = ctx.shared.package_index.with_workspace_of(inputs)
    result = expand(inputs, mappings=mappings, package_index=index)  # errors: exit 2
    for warning in result.warnings:
        print(warning.format(), file=sys.stderr)

    def work(thread: ThreadNode) -> int:
        if output:
            atomic_write_text(output, result.text)
        else:
            sys.stdout.write(result.text)
            sys.stdout.flush()
        return 0

    return ThreadNode(f"xacro {ctx.spec.fqn}", work, ctx.log)


def _xacro_args(args: tuple[str, ...]) -> tuple[str, str | None, dict[str, str]]:
    """xacro's command line: one input, ``name:=value`` mappings, ``-o OUT``."""
    inputs: list[str] = []
    output = None
    i = 0
    while i < len(args):
        word = args[i]
        if word == "-o" and i + 1 < len(args):
            output = args[i + 1]
            i += 1
        elif word in ("--inorder", "-i"):
            pass
        elif word.startswith("-"):
            raise RobomodelError(
                f"xacro: option {word} is not taken here; use `robomodel xacro` for all of "
                "xacro's options"
            )
        elif ":=" not in word:
            inputs.append(word)
        i += 1
    if len(inputs) != 1:
        found = " ".join(inputs) or "none"
        raise RobomodelError(f"xacro: expected exactly one input file, got: {found}")
    mappings = dict(word.split(":=", 1) for word in args if ":=" in word)
    return inputs[0], output, {k: v for k, v in mappings.items() if not k.startswith("_")}


for _dialect in ("ros1", "ros2"):
    register(
        _dialect, "xacro", "xacro", "xacro.py", purpose="prints the expanded URDF (xacro FILE)"
    )(_xacro)
