"""What ``ros2 launch --show-args`` finds without running: declared arguments, statically."""

from __future__ import annotations

from typing import Any

__all__ = ["launch_arguments"]


def launch_arguments(
    entities: list[Any], conditional_inclusion: bool = False
) -> list[tuple[Any, bool, list[Any] | None]]:
    """``(DeclareLaunchArgument, conditionally_included, include chain)`` in order.

    Transcribes ``LaunchDescription.get_launch_arguments_with_include_launch_description_actions``:
    the walk follows ``describe_sub_entities`` (includes whose file can be found without a
    context are loaded), marks declarations under a condition or an event handler as
    conditional, keeps the first declaration of a name and stops a branch at
    ``ResetLaunchConfigurations``.
    """
    from robomodel.launch.ros2.shim.actions import (
        DeclareLaunchArgument,
        IncludeLaunchDescription,
        ResetLaunchConfigurations,
    )

    found: list[tuple[Any, bool, list[Any] | None]] = []

    def walk(items: list[Any], conditional: bool, chain: list[Any] | None) -> None:
        for entity in items:
            if isinstance(entity, DeclareLaunchArgument):
                if any(entity.name == other.name for other, _, _ in found):
                    continue
                found.append((entity, conditional or entity.condition is not None, chain))
            if isinstance(entity, ResetLaunchConfigurations):
                return
            next_chain = chain
            if isinstance(entity, IncludeLaunchDescription):
                next_chain = [*(chain or []), entity]
            walk(entity.describe_sub_entities(), False, next_chain)
            for _, sub in entity.describe_conditional_sub_entities():
                walk(sub, True, next_chain)

    walk(entities, conditional_inclusion, None)
    return found
