"""A simulation server's controller managers across recompiles, and the state carried from
one compiled scene to the next (see :mod:`robomodel.sim.server`)."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from robomodel.control import ControlSystem
    from robomodel.control.config import ControllerSpec
    from robomodel.control.manager import ControllerManager
    from robomodel.runtime.context import Context
    from robomodel.sim.build.robot import Placement
    from robomodel.sim.engine import Simulation

__all__ = [
    "ControlledServer",
    "Controllers",
    "PlacedRobot",
    "carry_state",
    "namespace_of",
    "start_control",
]


class ControlledServer(Protocol):
    """What :func:`start_control` uses of the :class:`~robomodel.sim.server.SimServer`: the
    graph its controller managers join and where their controllers' parameters come from."""

    @property
    def context(self) -> Context: ...

    @property
    def spec_source(self) -> Callable[[str, str], ControllerSpec | None] | None: ...


class PlacedRobot(Protocol):
    """What :func:`start_control` reads of a :class:`~robomodel.sim.server.SpawnedRobot`."""

    @property
    def placement(self) -> Placement: ...

    @property
    def robot_namespace(self) -> str: ...


@dataclass(frozen=True, slots=True)
class Controllers:
    """What a robot's controller manager held before a recompile."""

    specs: dict[str, ControllerSpec]
    states: dict[str, str]


def start_control(
    server: ControlledServer, sim: Simulation, entry: PlacedRobot, previous: Controllers | None
) -> ControlSystem | None:
    """The robot's controller manager, as ``gazebo_ros_control`` (ROS 1) or
    ``gazebo_ros2_control`` starts one: only for a robot with the plugin or hardware."""
    from robomodel.control.config import ControllerConfig

    built = sim.robot(entry.placement.prefix)
    if not built.extensions.ros_control_plugin:
        return None
    namespace = namespace_of(built.extensions.plugin_namespace, entry.robot_namespace)
    config = ControllerConfig(namespace=namespace, format="ros1")
    files = built.extensions.plugin_parameters
    if files:  # gazebo_ros2_control: the manager's update_rate and controller types
        from robomodel.control.config import load_controller_config

        loaded = [load_controller_config(f) for f in files]
        config = dataclasses.replace(
            loaded[-1],
            namespace=namespace,
            controllers=tuple(c for part in loaded for c in part.controllers),
        )
    source = server.spec_source

    def prepare(manager: ControllerManager) -> None:
        # before the services are offered: a spawner's load_controller must find the
        # parameter server's controllers, and the controllers of the previous scene running
        if source is not None:
            manager.spec_source = lambda name: source(manager.namespace, name)
        if previous is not None:
            manager.specs.update(previous.specs)
            active = [n for n, s in previous.states.items() if s == "active"]
            for name, state in previous.states.items():
                if name not in active:
                    manager.load_controller(name)
                    if state == "inactive":
                        manager.configure_controller(name)
            manager.spawn(active)

    system = sim.control(
        config, prefix=entry.placement.prefix, context=server.context, spawn=[], prepare=prepare
    )
    return system


def namespace_of(plugin_namespace: str, robot_namespace: str) -> str:
    return "/" + (plugin_namespace or robot_namespace).strip("/")


def carry_state(old: Simulation, new: Simulation) -> None:
    """Joint positions and velocities (by name) and the time from ``old`` into ``new``."""
    from robomodel.sim._mujoco import mujoco

    mj = mujoco()
    om, od, nm, nd = old.model, old.data, new.model, new.data
    widths = {0: (7, 6), 1: (4, 3), 2: (1, 1), 3: (1, 1)}  # free, ball, slide, hinge
    for jid in range(om.njnt):
        name = mj.mj_id2name(om, mj.mjtObj.mjOBJ_JOINT, jid)
        new_id = mj.mj_name2id(nm, mj.mjtObj.mjOBJ_JOINT, name) if name else -1
        if new_id < 0 or nm.jnt_type[new_id] != om.jnt_type[jid]:
            continue
        nq, nv = widths[int(om.jnt_type[jid])]
        qa, na = om.jnt_qposadr[jid], nm.jnt_qposadr[new_id]
        nd.qpos[na : na + nq] = od.qpos[qa : qa + nq]
        va, nva = om.jnt_dofadr[jid], nm.jnt_dofadr[new_id]
        nd.qvel[nva : nva + nv] = od.qvel[va : va + nv]
    nd.time = od.time
    mj.mj_forward(nm, nd)
