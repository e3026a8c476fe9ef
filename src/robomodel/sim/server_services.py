"""The simulation server's gazebo_msgs services (as dicts): spawn, delete, world properties.

``/gazebo/spawn_urdf_model`` and ``/gazebo/spawn_sdf_model`` (gazebo_ros, ROS 1),
``/spawn_entity`` (gazebo_ros, ROS 2), ``/gazebo/delete_model`` and
``/gazebo/get_world_properties``. A failure is a reply with ``success: false`` and the reason in
``status_message``, never an exception in the server's process.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import TYPE_CHECKING, Any

from robomodel.errors import RobomodelError
from robomodel.sim.exceptions import SimulationError

if TYPE_CHECKING:
    from robomodel.sim.server import SimServer

__all__ = ["service_handlers"]

Handler = Callable[[dict[str, Any]], dict[str, Any]]


def service_handlers(server: SimServer) -> dict[str, Handler]:
    """The server's services by name, in the order they are offered."""
    return {
        "/gazebo/spawn_urdf_model": partial(spawn_urdf_model, server),
        "/spawn_entity": partial(spawn_entity, server),
        "/gazebo/spawn_sdf_model": partial(spawn_sdf_model, server),
        "/gazebo/delete_model": partial(delete_model, server),
        "/gazebo/get_world_properties": partial(get_world_properties, server),
    }


def spawn_urdf_model(server: SimServer, request: dict[str, Any]) -> dict[str, Any]:
    """gazebo_ros ``/gazebo/spawn_urdf_model``: ``model_name``, ``model_xml``,
    ``robot_namespace``, ``initial_pose`` [x, y, z, R, P, Y], ``joints``, ``unpause``."""
    try:
        pose = [float(v) for v in request.get("initial_pose", (0.0,) * 6)]
        if len(pose) != 6:
            raise SimulationError(f"initial_pose needs 6 numbers, got {len(pose)}")
        joints = {str(k): float(v) for k, v in dict(request.get("joints", {})).items()}
        server.spawn(
            str(request.get("model_name", "")) or "robot",
            str(request["model_xml"]),
            xyz_m=(pose[0], pose[1], pose[2]),
            rpy_rad=(pose[3], pose[4], pose[5]),
            joint_positions=joints,
            robot_namespace=str(request.get("robot_namespace", "/")),
        )
    except (RobomodelError, KeyError, TypeError, ValueError) as exc:
        return {"success": False, "status_message": f"SpawnModel: {exc}"}
    if request.get("unpause") and server.bridge is not None:
        server.bridge.paused = False
    return {"success": True, "status_message": "SpawnModel: Successfully spawned entity"}


def spawn_entity(server: SimServer, request: dict[str, Any]) -> dict[str, Any]:
    """gazebo_ros (ROS 2) ``/spawn_entity``: ``name``, ``xml``, ``robot_namespace``,
    ``initial_pose`` [x, y, z, R, P, Y]."""
    renamed = {
        "model_name": request.get("name", ""),
        "model_xml": request.get("xml", ""),
        "robot_namespace": request.get("robot_namespace", "/"),
        "initial_pose": request.get("initial_pose", (0.0,) * 6),
        "unpause": request.get("unpause", False),
    }
    reply = spawn_urdf_model(server, renamed)
    message = str(reply["status_message"]).replace("SpawnModel: ", "SpawnEntity: ")
    return {"success": reply["success"], "status_message": message}


def spawn_sdf_model(server: SimServer, request: dict[str, Any]) -> dict[str, Any]:
    """gazebo_ros ``/gazebo/spawn_sdf_model``: ``model_name``, ``model_xml``, ``initial_pose``."""
    try:
        pose = [float(v) for v in request.get("initial_pose", (0.0,) * 6)]
        server.spawn_sdf(
            str(request.get("model_name", "")) or "model",
            str(request["model_xml"]),
            xyz_m=(pose[0], pose[1], pose[2]),
            rpy_rad=(pose[3], pose[4], pose[5]),
        )
    except (RobomodelError, KeyError, TypeError, ValueError, IndexError) as exc:
        return {"success": False, "status_message": f"SpawnModel: {exc}"}
    return {"success": True, "status_message": "SpawnModel: Successfully spawned entity"}


def delete_model(server: SimServer, request: dict[str, Any]) -> dict[str, Any]:
    """gazebo_ros ``/gazebo/delete_model``: ``model_name``."""
    try:
        server.delete(str(request.get("model_name", "")))
    except RobomodelError as exc:
        return {"success": False, "status_message": f"DeleteModel: {exc}"}
    return {"success": True, "status_message": "DeleteModel: successfully deleted model"}


def get_world_properties(server: SimServer, request: dict[str, Any]) -> dict[str, Any]:
    """gazebo_ros ``/gazebo/get_world_properties``: the sim time and the robots' names."""
    assert server.sim is not None
    return {
        "sim_time": server.sim.time_s,
        "model_names": [r.model_name for r in server.robots],
        "rendering_enabled": False,
        "success": True,
    }
