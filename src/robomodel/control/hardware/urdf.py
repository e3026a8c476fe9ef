"""Hardware components from a robot description.

``<ros2_control>`` blocks become components as ros2_control's component_parser reads them.
A description without any but with ROS 1 ``<transmission>`` tags gets one mock system derived
from them, as gazebo_ros_control's DefaultRobotHWSim did: each transmission joint gets the
command interface its ``<hardwareInterface>`` names (Effort/Position/Velocity), and position,
velocity and effort states. That system has ``calculate_dynamics`` on, so effort commands move
the joints through the robot's rigid-body dynamics (see :mod:`.mock`).
"""

from __future__ import annotations

import logging
import math
import warnings
from collections.abc import Callable

from robomodel.control.hardware.base import ComponentInfo, HardwareComponent, HardwareInfo
from robomodel.control.hardware.exceptions import HardwareError
from robomodel.control.hardware.interfaces import (
    EFFORT,
    POSITION,
    VELOCITY,
    InterfaceDescription,
)
from robomodel.control.hardware.mock import GenericSystem
from robomodel.description.model import ComponentInterfaces, Interface, JointType, Robot
from robomodel.errors import close_matches

__all__ = [
    "HARDWARE_PLUGINS",
    "HardwareFactory",
    "hardware_from_robot",
    "hardware_infos_from_robot",
    "register_hardware_plugin",
]

log = logging.getLogger("robomodel.control")

HardwareFactory = Callable[[HardwareInfo, Robot], HardwareComponent]

# Simulator plugins run as mock hardware with dynamics until a simulator registers itself.
_SIMULATOR_PLUGINS = (
    "gazebo_ros2_control/GazeboSystem",
    "gz_ros2_control/GazeboSimSystem",
    "ign_ros2_control/IgnitionSystem",
)


def _mock_factory(info: HardwareInfo, robot: Robot) -> HardwareComponent:
    from robomodel.kinematics import Kinematics

    kin = Kinematics(robot)
    try:
        dynamics = kin.dynamics()
    except Exception:  # floating bases: no rigid-body integration for effort joints
        dynamics = None
    damping = {
        j.name: (j.dynamics.damping or 0.0) if j.dynamics is not None else 0.0 for j in robot.joints
    }
    mimic = {name: spec for name, spec in kin.mimic.items()}
    return GenericSystem(info, mimic=mimic, dynamics=dynamics, damping=damping)


def _simulator_factory(info: HardwareInfo, robot: Robot) -> HardwareComponent:
    log.info(
        "hardware '%s' uses %s; no simulator is running, so mock hardware with "
        "calculate_dynamics stands in for it",
        info.name,
        info.plugin,
    )
    params = dict(info.params)
    params.setdefault("calculate_dynamics", "true")
    return _mock_factory(
        HardwareInfo(
            info.name,
            info.type,
            info.plugin,
            params,
            info.joints,
            info.sensors,
            info.gpios,
            info.source,
        ),
        robot,
    )


HARDWARE_PLUGINS: dict[str, HardwareFactory] = {
    "mock_components/GenericSystem": _mock_factory,
    "fake_components/GenericSystem": _mock_factory,  # foxy/galactic name
    **{name: _simulator_factory for name in _SIMULATOR_PLUGINS},
}


def register_hardware_plugin(name: str, factory: HardwareFactory) -> None:
    """Make ``<plugin>name</plugin>`` build components with ``factory`` (e.g. a simulator)."""
    HARDWARE_PLUGINS[name] = factory


def _float(text: str | None, what: str, where: str) -> float | None:
    if text is None or text.strip() == "":
        return None
    try:
        return float(text)
    except ValueError:
        raise HardwareError(f"{where}: {what} must be a number, got {text!r}") from None


def _describe(
    prefix: str, iface: Interface, where: str, robot: Robot, command: bool
) -> InterfaceDescription:
    init = _float(iface.initial_value, f"initial_value of {prefix}/{iface.name}", where)
    lo = _float(iface.min, f"min of {prefix}/{iface.name}", where)
    hi = _float(iface.max, f"max of {prefix}/{iface.name}", where)
    lo = -math.inf if lo is None else lo
    hi = math.inf if hi is None else hi
    if command and robot.has_joint(prefix):
        lo, hi = _tighten(robot, prefix, iface.name, lo, hi)
    return InterfaceDescription(prefix, iface.name, iface.data_type or "double", init, lo, hi)


def _tighten(
    robot: Robot, joint_name: str, iface: str, lo: float, hi: float
) -> tuple[float, float]:
    """Most restrictive of the interface's min/max and the URDF ``<limit>``.

    ros2_control ``update_interface_limits``: position ``[max(min, lower), min(max, upper)]``
    (not for continuous joints); velocity and effort ``±min(|min|, max, urdf)``.
    """
    joint = robot.joint(joint_name)
    limit = joint.limit
    if limit is None:
        return lo, hi
    if iface == POSITION and joint.type in (JointType.REVOLUTE, JointType.PRISMATIC):
        return max(lo, limit.lower_or_default), min(hi, limit.upper_or_default)
    if iface in (VELOCITY, EFFORT):
        urdf = limit.velocity if iface == VELOCITY else limit.effort
        if urdf is not None and urdf > 0:  # 0 in URDF files usually means "not given"
            m = min(abs(lo), hi, urdf)
            return -m, m
    return lo, hi


def _component(
    comp: ComponentInterfaces, where: str, robot: Robot, is_joint: bool
) -> ComponentInfo:
    if is_joint:
        if not robot.has_joint(comp.name):
            hint = close_matches(comp.name, robot.joint_names)
            raise HardwareError(
                f"{where}: <ros2_control> joint '{comp.name}' is not in the URDF"
                + (f" (did you mean {', '.join(repr(h) for h in hint)}?)" if hint else "")
            )
        if robot.joint(comp.name).type is JointType.FIXED:
            raise HardwareError(f"{where}: <ros2_control> joint '{comp.name}' is a fixed joint")
    return ComponentInfo(
        comp.name,
        tuple(_describe(comp.name, i, where, robot, True) for i in comp.command_interfaces),
        tuple(_describe(comp.name, i, where, robot, False) for i in comp.state_interfaces),
        comp.params,
    )


def _where(span: object, fallback: str) -> str:
    location = getattr(span, "location", None)
    return str(location) if location is not None else fallback


_ROS1_INTERFACES = {
    "EffortJointInterface": EFFORT,
    "PositionJointInterface": POSITION,
    "VelocityJointInterface": VELOCITY,
}


def _from_transmissions(robot: Robot) -> HardwareInfo | None:
    joints: list[ComponentInfo] = []
    seen: set[str] = set()
    for t in robot.transmissions:
        where = _where(t.span, f"transmission '{t.name}'")
        for tj in t.joints:
            if tj.name in seen or not robot.has_joint(tj.name):
                continue
            seen.add(tj.name)
            commands: list[str] = []
            for hw in tj.hardware_interfaces:
                kind = _ROS1_INTERFACES.get(hw.split("/")[-1])
                if kind is None:
                    log.warning("%s: hardware interface '%s' is not supported; ignored", where, hw)
                elif kind not in commands:
                    commands.append(kind)
            if not commands:
                continue
            cmd = tuple(
                InterfaceDescription(
                    tj.name, k, "double", None, *_tighten(robot, tj.name, k, -math.inf, math.inf)
                )
                for k in commands
            )
            states = tuple(InterfaceDescription(tj.name, k) for k in (POSITION, VELOCITY, EFFORT))
            joints.append(ComponentInfo(tj.name, cmd, states))
    if not joints:
        return None
    return HardwareInfo(
        name=f"{robot.name}_transmissions",
        type="system",
        plugin="mock_components/GenericSystem",
        params={"calculate_dynamics": "true"},
        joints=tuple(joints),
        source="<transmission> tags",
    )


def hardware_infos_from_robot(robot: Robot) -> list[HardwareInfo]:
    """One :class:`HardwareInfo` per ``<ros2_control>`` block (or from the transmissions)."""
    infos: list[HardwareInfo] = []
    for block in robot.ros2_control:
        where = _where(block.span, f"<ros2_control name='{block.name}'>")
        plugin = (block.hardware_plugin or "").strip()
        if not plugin:
            raise HardwareError(f"{where}: <ros2_control name='{block.name}'> has no <plugin>")
        infos.append(
            HardwareInfo(
                name=block.name,
                type=block.type,
                plugin=plugin.replace(" ", "_") if plugin.startswith("fake components") else plugin,
                params=dict(block.hardware_params),
                joints=tuple(_component(j, where, robot, True) for j in block.joints),
                sensors=tuple(_component(s, where, robot, False) for s in block.sensors),
                gpios=tuple(_component(g, where, robot, False) for g in block.gpios),
                source=where,
            )
        )
    if not infos:
        derived = _from_transmissions(robot)
        if derived is not None:
            infos.append(derived)
    return infos


def hardware_from_robot(robot: Robot, *, unknown_as_mock: bool = False) -> list[HardwareComponent]:
    """Build the hardware components of ``robot`` (see the module docstring).

    ``unknown_as_mock``: a plugin robomodel does not have (a package's own C++ system, as in
    ros2_control's demos) runs as ``mock_components/GenericSystem`` over the interfaces its tag
    declares, with one warning naming it, instead of being an error.

    Raises:
        HardwareError: unknown plugin, joints missing from the URDF, bad numbers.
    """
    components: list[HardwareComponent] = []
    for info in hardware_infos_from_robot(robot):
        factory = HARDWARE_PLUGINS.get(info.plugin)
        if factory is None and unknown_as_mock:
            warnings.warn(
                f"{info.source}: hardware plugin '{info.plugin}' is not available in robomodel; "
                f"'{info.name}' runs as mock_components/GenericSystem over the interfaces its "
                "<ros2_control> tag declares",
                stacklevel=2,
            )
            factory = HARDWARE_PLUGINS["mock_components/GenericSystem"]
        if factory is None:
            hint = close_matches(info.plugin, HARDWARE_PLUGINS)
            raise HardwareError(
                f"{info.source}: unknown hardware plugin '{info.plugin}'"
                + (f" (did you mean {', '.join(repr(h) for h in hint)}?)" if hint else "")
                + f"; known plugins: {', '.join(sorted(HARDWARE_PLUGINS))}"
            )
        components.append(factory(info, robot))
    return components
