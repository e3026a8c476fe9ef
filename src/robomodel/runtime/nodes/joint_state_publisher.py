"""joint_state_publisher, with the parameters and semantics of ROS 2's (ros/joint_state_publisher).

Free joints are every revolute, continuous and prismatic joint that is not a mimic (fixed,
floating and planar joints are skipped, as upstream does); continuous joints range over
[-pi, pi]. Each tick publishes every joint in URDF order; dependent (mimic) joints follow their
source through whole chains (a cycle is an error). ``set_positions`` is the programmatic
equivalent of joint_state_publisher_gui's sliders.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from robomodel.description.model import JointType, Robot
from robomodel.errors import RobomodelError
from robomodel.runtime.context import Context
from robomodel.runtime.msg import JointState, String
from robomodel.runtime.node import Node
from robomodel.runtime.params import SetResult
from robomodel.runtime.qos import latched

__all__ = ["FreeJoint", "JointStatePublisher", "MimicChainError"]

_SKIPPED = (JointType.FIXED, JointType.FLOATING, JointType.PLANAR)


class MimicChainError(RobomodelError):
    """A mimic chain that loops back on itself."""

    def __init__(self, chain: list[str]) -> None:
        self.chain = chain
        super().__init__(f"Found an infinite recursive mimic chain: {chain}")


@dataclass
class FreeJoint:
    """One slider of joint_state_publisher_gui: range [min, max], centre ``zero``."""

    name: str
    min: float
    max: float
    zero: float
    continuous: bool
    position: float | None
    velocity: float | None = None
    effort: float | None = None
    forward: bool = True


@dataclass(frozen=True, slots=True)
class Dependent:
    parent: str
    factor: float = 1.0
    offset: float = 0.0


def _free_joints(
    robot: Robot,
    zeros: Mapping[str, float],
    *,
    use_mimic: bool,
    smallest_limits: bool,
    default_positions: bool,
    default_velocities: bool,
    default_efforts: bool,
) -> tuple[dict[str, FreeJoint], dict[str, Dependent], list[str]]:
    free: dict[str, FreeJoint] = {}
    dependent: dict[str, Dependent] = {}
    order: list[str] = []
    for joint in robot.joints:
        if joint.type in _SKIPPED:
            continue
        if joint.type is JointType.CONTINUOUS:
            low, high = -math.pi, math.pi
        else:
            limit = joint.limit
            if limit is None:
                raise RobomodelError(
                    f'Limits must be specified for joint "{joint.name}" of type "{joint.type.value}"'
                )
            if limit.lower is None:
                raise RobomodelError(f'"lower" limit must be specified for joint "{joint.name}"')
            if limit.upper is None:
                raise RobomodelError(f'"upper" limit must be specified for joint "{joint.name}"')
            low, high = limit.lower, limit.upper
            safety = joint.safety_controller
            if smallest_limits and safety is not None:
                if safety.soft_lower_limit is not None:
                    low = max(low, safety.soft_lower_limit)
                if safety.soft_upper_limit is not None:
                    high = min(high, safety.soft_upper_limit)
        order.append(joint.name)
        if use_mimic and joint.mimic is not None:
            dependent[joint.name] = Dependent(
                joint.mimic.joint, joint.mimic.multiplier_or_default, joint.mimic.offset_or_default
            )
            continue
        if joint.name in zeros:
            zero = float(zeros[joint.name])
        elif low > 0 or high < 0:
            zero = (low + high) / 2
        else:
            zero = 0.0
        free[joint.name] = FreeJoint(
            joint.name,
            low,
            high,
            zero,
            joint.type is JointType.CONTINUOUS,
            zero if default_positions else None,
            0.0 if default_velocities else None,
            0.0 if default_efforts else None,
        )
    return free, dependent, order


def resolve_dependent(name: str, dependent: Mapping[str, Dependent]) -> tuple[str, float, float]:
    """Follow a mimic chain to its free source: ``(source, factor, offset)``."""
    entry = dependent[name]
    parent, factor, offset = entry.parent, entry.factor, entry.offset
    chain = [name]
    while parent in dependent:
        if parent in chain:
            raise MimicChainError([*chain, parent])
        chain.append(parent)
        entry = dependent[parent]
        parent = entry.parent
        offset += factor * entry.offset
        factor *= entry.factor
    return parent, factor, offset


class JointStatePublisher:
    """The joint_state_publisher node.

    Args:
        context: Where the node lives.
        robot: The description; without one, the node waits for /robot_description.
        name: Node name.
        parameters: Overrides for ``rate``, ``zeros.<joint>``, ``source_list``,
            ``use_mimic_tags``, ``use_smallest_joint_limits``, ``publish_default_positions``,
            ``publish_default_velocities``, ``publish_default_efforts``, ``delta``,
            ``dependent_joints.<joint>.{parent,factor,offset}``.
    """

    def __init__(
        self,
        context: Context,
        robot: Robot | None = None,
        *,
        name: str = "joint_state_publisher",
        namespace: str = "/",
        parameters: Mapping[str, Any] | None = None,
        remappings: Mapping[str, str] | None = None,
    ) -> None:
        self.node: Node = context.create_node(
            name,
            namespace,
            parameters=parameters,
            remappings=remappings,
            allow_undeclared_parameters=True,
        )
        node = self.node
        self.rate_hz = float(node.declare_parameter("rate", 10))
        self.use_mimic = bool(node.declare_parameter("use_mimic_tags", True))
        self.smallest_limits = bool(node.declare_parameter("use_smallest_joint_limits", True))
        self.default_positions = bool(node.declare_parameter("publish_default_positions", True))
        self.default_velocities = bool(node.declare_parameter("publish_default_velocities", False))
        self.default_efforts = bool(node.declare_parameter("publish_default_efforts", False))
        self.delta = float(node.declare_parameter("delta", 0.0))
        sources = node.declare_parameter("source_list", [])
        self.free_joints: dict[str, FreeJoint] = {}
        self.dependent_joints: dict[str, Dependent] = {}
        self.joint_list: list[str] = []
        self.publisher = node.create_publisher(JointState, "joint_states", 10)
        for topic in sources:
            node.create_subscription(JointState, str(topic), self._source_cb, 10)
        node.create_subscription(String, "robot_description", self._description_cb, latched())
        node.parameters.add_set_callback(self._check_parameters)
        node.parameters.add_post_set_callback(self._apply_parameters)
        if robot is not None:
            self.configure(robot)
        self._timer = node.create_timer(1.0 / self.rate_hz, self.publish)

    # -- configuration ------------------------------------------------------------------------
    def _zeros(self) -> dict[str, float]:
        prefix = "zeros."
        return {
            n[len(prefix) :]: float(self.node.get_parameter(n))
            for n in self.node.parameters.names(prefix)
        }

    def _parameter_dependents(self) -> dict[str, Dependent]:
        out: dict[str, Dependent] = {}
        prefix = "dependent_joints."
        grouped: dict[str, dict[str, Any]] = {}
        for n in self.node.parameters.names(prefix):
            joint, _, key = n[len(prefix) :].rpartition(".")
            if key not in ("parent", "factor", "offset"):
                raise RobomodelError(
                    f"dependent_joints.{joint}: unknown key '{key}' (parent, factor, offset)"
                )
            grouped.setdefault(joint, {})[key] = self.node.get_parameter(n)
        for joint, keys in grouped.items():
            if "parent" not in keys:
                raise RobomodelError(f"dependent_joints.{joint} needs a 'parent'")
            out[joint] = Dependent(
                str(keys["parent"]), float(keys.get("factor", 1.0)), float(keys.get("offset", 0.0))
            )
        return out

    def configure(self, robot: Robot) -> None:
        """(Re)build the joint table from a description, keeping positions of joints that remain."""
        old = self.free_joints
        free, dependent, order = _free_joints(
            robot,
            self._zeros(),
            use_mimic=self.use_mimic,
            smallest_limits=self.smallest_limits,
            default_positions=self.default_positions,
            default_velocities=self.default_velocities,
            default_efforts=self.default_efforts,
        )
        dependent.update(self._parameter_dependents())
        for name in dependent:
            free.pop(name, None)
            resolve_dependent(name, dependent)  # raises MimicChainError on a cycle
            if resolve_dependent(name, dependent)[0] not in free:
                raise RobomodelError(
                    f"joint '{name}' mimics '{dependent[name].parent}', which is not a movable joint"
                )
        for name, joint in free.items():
            if name in old and old[name].position is not None:
                joint.position = min(max(old[name].position or 0.0, joint.min), joint.max)
        self.free_joints, self.dependent_joints, self.joint_list = free, dependent, order

    def _description_cb(self, msg: String) -> None:
        from robomodel.description import read_urdf

        try:
            self.configure(read_urdf(msg.data, path="robot_description").robot)
        except RobomodelError as exc:
            self.node.logger.error("cannot use the new robot_description: %s", exc)

    def _check_parameters(self, changes: Mapping[str, Any]) -> SetResult:
        if "rate" in changes and not float(changes["rate"]) > 0:
            return SetResult(False, "rate must be > 0")
        return SetResult(True)

    def _apply_parameters(self, changes: Mapping[str, Any]) -> None:
        if "rate" in changes:
            self.rate_hz = float(changes["rate"])
            self._timer.cancel()
            self._timer = self.node.create_timer(1.0 / self.rate_hz, self.publish)
        if "delta" in changes:
            self.delta = float(changes["delta"])

    # -- inputs -------------------------------------------------------------------------------
    def _source_cb(self, msg: JointState) -> None:
        for i, name in enumerate(msg.name):
            joint = self.free_joints.get(name)
            if joint is None:
                continue
            if i < len(msg.position):
                joint.position = msg.position[i]
            if i < len(msg.velocity):
                joint.velocity = msg.velocity[i]
            if i < len(msg.effort):
                joint.effort = msg.effort[i]

    def set_positions(self, positions: Mapping[str, float], *, clamp: bool = True) -> None:
        """Set free joints (what the GUI sliders do); unknown names raise with the valid ones."""
        for name, value in positions.items():
            joint = self.free_joints.get(name)
            if joint is None:
                valid = ", ".join(self.free_joints) or "(none)"
                hint = (
                    " (a mimic joint follows its source)" if name in self.dependent_joints else ""
                )
                raise RobomodelError(f"'{name}' is not a free joint{hint}; free joints: {valid}")
            if not math.isfinite(value):
                raise RobomodelError(f"joint '{name}': position must be finite, got {value}")
            joint.position = min(max(value, joint.min), joint.max) if clamp else value

    def center(self) -> None:
        """Every free joint to its zero (the GUI's Center button)."""
        for joint in self.free_joints.values():
            joint.position = joint.zero

    def randomize(self, rng: random.Random | None = None) -> None:
        """Every free joint to a uniform random value in its range (the GUI's Randomize)."""
        generator = rng or random.Random()
        for joint in self.free_joints.values():
            joint.position = generator.uniform(joint.min, joint.max)

    def sweep(self, delta: float) -> None:
        """Move every free joint by ``delta``, bouncing at limits (the ``delta`` parameter)."""
        for joint in self.free_joints.values():
            position = joint.position or 0.0
            if joint.forward:
                position += delta
                if position > joint.max:
                    if joint.continuous:
                        position = joint.min
                    else:
                        position = joint.max
                        joint.forward = False
            else:
                position -= delta
                if position < joint.min:
                    position = joint.min
                    joint.forward = True
            joint.position = position

    # -- output -------------------------------------------------------------------------------
    def positions(self) -> dict[str, float]:
        """Current position of every joint in the message (free and dependent)."""
        msg = self.make_message()
        return dict(zip(msg.name, msg.position, strict=False))

    def make_message(self) -> JointState:
        """The JointState the next tick would publish (without advancing ``delta``)."""
        msg = JointState()
        msg.header.stamp = self.node.now()
        has_position = bool(self.dependent_joints) or any(
            j.position is not None for j in self.free_joints.values()
        )
        has_velocity = any(j.velocity is not None for j in self.free_joints.values())
        has_effort = any(j.effort is not None for j in self.free_joints.values())
        count = len(self.joint_list)
        msg.position = [0.0] * count if has_position else []
        msg.velocity = [0.0] * count if has_velocity else []
        msg.effort = [0.0] * count if has_effort else []
        for i, name in enumerate(self.joint_list):
            msg.name.append(name)
            if name in self.free_joints:
                joint, factor, offset = self.free_joints[name], 1.0, 0.0
            else:
                source, factor, offset = resolve_dependent(name, self.dependent_joints)
                joint = self.free_joints[source]
            if has_position and joint.position is not None:
                msg.position[i] = float(joint.position) * factor + offset
            if has_velocity and joint.velocity is not None:
                msg.velocity[i] = float(joint.velocity) * factor
            if has_effort and joint.effort is not None:
                msg.effort[i] = float(joint.effort)
        return msg

    def publish(self) -> None:
        """One tick: apply ``delta``, then publish (empty messages are not published)."""
        if self.delta > 0:
            self.sweep(self.delta)
        msg = self.make_message()
        if msg.name or msg.position or msg.velocity or msg.effort:
            self.publisher.publish(msg)

    def publish_now(self) -> None:
        """Publish out of turn (a slider moved) and restart the ``rate`` timer.

        ROS's node publishes only on its timer, so joint_state_publisher_gui's sliders are
        seen at ``rate`` (10 Hz). A slider here is published when it moves; restarting the
        timer keeps at least ``rate`` messages a second without a tick repeating the values
        just sent (each /joint_states costs robot_state_publisher and every TF listener).
        """
        self.publish()
        self._timer.reset()
