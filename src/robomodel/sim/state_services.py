"""gazebo_ros's state services and topics (``gazebo_ros_api_plugin``, noetic-devel) on the
models and links of :class:`~robomodel.sim.states.WorldStates`:

=====================================  ======================================================
``/gazebo/get_model_state``            gazebo_msgs/GetModelState (relative to an entity)
``/gazebo/get_link_state``             gazebo_msgs/GetLinkState (``model::link``)
``/gazebo/set_link_state``             gazebo_msgs/SetLinkState, and a LinkState topic
``/gazebo/set_model_state`` (topic)    gazebo_msgs/ModelState, as the service
``/gazebo/get_model_properties``       gazebo_msgs/GetModelProperties
=====================================  ======================================================

Replies and status messages are gazebo_ros's. An empty, ``world`` or ``map`` reference frame is
the world; another names a model or link. A link is set only where MuJoCo can place it freely
(a floating model's root link, a world object): Gazebo also moves links that hang on joints,
which the joints then pull back; robomodel refuses that with a reason instead. The changes are
applied by the simulation loop at its next tick, as every state-changing request.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from robomodel.runtime.msg.types import gazebo_msgs as gz
from robomodel.runtime.msg.types.std_msgs import Header
from robomodel.sim._mujoco import mujoco

if TYPE_CHECKING:
    from robomodel.sim.bus_services import ServedBridge
    from robomodel.sim.states import Entity, WorldStates

__all__ = ["state_services", "state_topics"]

_WORLD_FRAMES = ("", "world", "map", "/map")


def _frame(states: WorldStates, name: str) -> tuple[bool, Entity | None]:
    """(known, entity): the world (None) or a model or link; unknown names are not known."""
    entity = states.entity(name)
    return (entity is not None or name in _WORLD_FRAMES), entity


def get_model_state(bridge: ServedBridge, request: gz.GetModelState_Request) -> Any:
    states = bridge.states
    model = states.model(request.model_name)
    if model is None:
        return gz.GetModelState_Response(
            success=False, status_message="GetModelState: model does not exist"
        )
    known, frame = _frame(states, request.relative_entity_name)
    if not known:
        return gz.GetModelState_Response(
            success=False,
            status_message="GetModelState: reference relative_entity_name not found, did you "
            "forget to scope the body by model name?",
        )
    pose, twist = (
        states.pose_twist(model.frame) if frame is None else states.relative(model.frame, frame)
    )
    from robomodel.runtime.msg.types.builtin_interfaces import Time

    header = Header(
        stamp=Time.from_seconds(bridge.sim.time_s), frame_id=request.relative_entity_name
    )
    return gz.GetModelState_Response(
        header, pose, twist, success=True, status_message="GetModelState: got properties"
    )


def get_link_state(bridge: ServedBridge, request: gz.GetLinkState_Request) -> Any:
    states = bridge.states
    link = states.entity(request.link_name)
    if link is None or states.model(request.link_name) is not None:
        return gz.GetLinkState_Response(
            success=False,
            status_message="GetLinkState: link not found, did you forget to scope the link by "
            "model name?",
        )
    known, frame = _frame(states, request.reference_frame)
    if not known:
        return gz.GetLinkState_Response(
            success=False,
            status_message="GetLinkState: reference reference_frame not found, did you forget "
            "to scope the link by model name?",
        )
    pose, twist = states.pose_twist(link) if frame is None else states.relative(link, frame)
    state = gz.LinkState(request.link_name, pose, twist, request.reference_frame)
    return gz.GetLinkState_Response(state, True, "GetLinkState: got state")


def get_model_properties(bridge: ServedBridge, request: gz.GetModelProperties_Request) -> Any:
    model = bridge.states.model(request.model_name)
    if model is None:
        return gz.GetModelProperties_Response(
            success=False, status_message="GetModelProperties: model does not exist"
        )
    return gz.GetModelProperties_Response(
        body_names=[link.name.split("::", 1)[1] for link in model.links],
        geom_names=list(model.geoms),
        joint_names=list(model.joints),
        is_static=model.is_static,
        success=True,
        status_message="GetModelProperties: got properties",
    )


def set_link_state(bridge: ServedBridge, request: gz.SetLinkState_Request) -> Any:
    state = request.link_state
    states = bridge.states
    link = states.entity(state.link_name)
    if link is None or states.model(state.link_name) is not None:
        return gz.SetLinkState_Response(False, "SetLinkState: link does not exist")
    known, frame = _frame(states, state.reference_frame)
    if not known:
        return gz.SetLinkState_Response(False, "SetLinkState: failed")
    free = _free_joint(bridge, link.body)
    if free is None:
        return gz.SetLinkState_Response(
            False,
            f"SetLinkState: link {state.link_name} hangs on a joint: robomodel moves only free "
            "bodies (a floating model's root link, a world object); set its joints with "
            "/gazebo/set_model_configuration",
        )
    target = _in_world(states, state.pose, state.twist, frame)
    bridge.queue(lambda: _place(bridge, free, *target))
    return gz.SetLinkState_Response(True, "SetLinkState: success")


def _free_joint(bridge: ServedBridge, body: int | None) -> int | None:
    """The free joint that places ``body``, if it has one."""
    if body is None:
        return None
    model = bridge.sim.model
    jid = int(model.body_jntadr[body])
    if jid < 0 or int(model.jnt_type[jid]) != int(mujoco().mjtJoint.mjJNT_FREE):
        return None
    return jid


def _in_world(
    states: WorldStates, pose: Any, twist: Any, frame: Entity | None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A pose (position, ``xyzw``) and twist given in ``frame`` as world values: the pose
    composed with the frame's, the twist less the frame's own velocity (gazebo_ros's
    set_link_state)."""
    from robomodel.kinematics.se3 import matrix_from_quat_xyzw, quat_xyzw_from_matrix

    p = np.array([pose.position.x, pose.position.y, pose.position.z])
    o = pose.orientation
    q = np.array([o.x, o.y, o.z, o.w]) if (o.x, o.y, o.z, o.w) != (0, 0, 0, 0) else np.eye(4)[3]
    q = q / np.linalg.norm(q)  # gazebo_ros normalises (an unset quaternion is no rotation)
    v = np.array([twist.linear.x, twist.linear.y, twist.linear.z])
    w = np.array([twist.angular.x, twist.angular.y, twist.angular.z])
    if frame is None:
        return p, q, v, w
    ref_pose, ref_twist = states.pose_twist(frame)
    r = ref_pose.orientation
    R = matrix_from_quat_xyzw([r.x, r.y, r.z, r.w])
    p0 = np.array([ref_pose.position.x, ref_pose.position.y, ref_pose.position.z])
    q = quat_xyzw_from_matrix(R @ matrix_from_quat_xyzw(q))
    v = v - np.array([ref_twist.linear.x, ref_twist.linear.y, ref_twist.linear.z])
    w = w - np.array([ref_twist.angular.x, ref_twist.angular.y, ref_twist.angular.z])
    return p0 + R @ p, q, v, w


def _place(
    bridge: ServedBridge,
    joint: int,
    p: np.ndarray,
    q_xyzw: np.ndarray,
    v: np.ndarray,
    w: np.ndarray,
) -> None:
    """Put a free body at ``p``, ``q_xyzw`` with world velocities ``v``, ``w``."""
    from robomodel.kinematics.se3 import matrix_from_quat_xyzw

    mj = mujoco()
    model, data = bridge.sim.model, bridge.sim.data
    qa, da = int(model.jnt_qposadr[joint]), int(model.jnt_dofadr[joint])
    data.qpos[qa : qa + 3] = p
    data.qpos[qa + 3 : qa + 7] = [q_xyzw[3], q_xyzw[0], q_xyzw[1], q_xyzw[2]]
    data.qvel[da : da + 3] = v  # a free joint: linear velocity in the world frame ...
    data.qvel[da + 3 : da + 6] = matrix_from_quat_xyzw(q_xyzw).T @ w  # ... angular in the body's
    mj.mj_forward(model, data)


def state_services(bridge: ServedBridge) -> list[tuple[str, Any, Callable[[Any], Any]]]:
    """(name, type, handler) of the state services (the module docstring's table)."""
    return [
        ("/gazebo/get_model_state", gz.GetModelState, lambda r: get_model_state(bridge, r)),
        ("/gazebo/get_link_state", gz.GetLinkState, lambda r: get_link_state(bridge, r)),
        ("/gazebo/set_link_state", gz.SetLinkState, lambda r: set_link_state(bridge, r)),
        ("/gazebo/get_model_properties", gz.GetModelProperties,
         lambda r: get_model_properties(bridge, r)),
    ]  # fmt: skip


def state_topics(bridge: ServedBridge) -> list[tuple[str, Any, Callable[[Any], Any]]]:
    """(topic, type, callback) of the set_model_state / set_link_state subscribers."""
    from robomodel.sim.bus_services import set_model_state

    return [
        ("/gazebo/set_link_state", gz.LinkState,
         lambda m: set_link_state(bridge, gz.SetLinkState_Request(m))),
        ("/gazebo/set_model_state", gz.ModelState,
         lambda m: set_model_state(bridge, gz.SetModelState_Request(m))),
    ]  # fmt: skip
