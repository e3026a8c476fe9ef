"""The simulation server's world services with their gazebo_msgs types: spawn, delete, model
configuration and world properties, under gazebo_ros's ROS 1 names (``/gazebo/...``) and, on a
ROS 2 graph, its ROS 2 names (``/spawn_entity``, ``/delete_entity``, ``/get_model_list``).

A failure is a reply with ``success: false`` and the reason in ``status_message`` (prefixed
with the service type, as gazebo_ros words it), never an exception in the server's process.
``SpawnEntity``'s XML is a URDF (``<robot>``) or an SDF model (``<sdf>``), as in gazebo_ros.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol

from robomodel.errors import RobomodelError
from robomodel.runtime.msg.types import gazebo_msgs as gz
from robomodel.runtime.msg.types.geometry_msgs import Pose
from robomodel.runtime.msg.types.std_msgs import Header
from robomodel.sim.bus_services import rpy_from_quaternion_xyzw

if TYPE_CHECKING:
    from robomodel.sim.engine import Simulation

__all__ = ["WorldServer", "service_handlers"]

Handler = Callable[[Any], Any]
_ERRORS = (RobomodelError, KeyError, TypeError, ValueError, IndexError)


class WorldServer(Protocol):
    """What the world services use of the :class:`~robomodel.sim.server.SimServer` that offers
    them."""

    @property
    def sim(self) -> Simulation | None: ...

    @property
    def ros_version(self) -> int: ...

    def spawn(
        self,
        model_name: str,
        urdf_xml: str,
        *,
        xyz_m: tuple[float, float, float],
        rpy_rad: tuple[float, float, float],
        robot_namespace: str,
    ) -> object: ...

    def spawn_sdf(
        self,
        model_name: str,
        sdf_xml: str,
        *,
        xyz_m: tuple[float, float, float],
        rpy_rad: tuple[float, float, float],
    ) -> None: ...

    def delete(self, model_name: str) -> None: ...

    def model_names(self) -> list[str]: ...

    def set_joint_positions(self, model_name: str, positions: dict[str, float]) -> None: ...


def _pose(pose: Pose) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    p, q = pose.position, pose.orientation
    if (q.x, q.y, q.z, q.w) == (0.0, 0.0, 0.0, 0.0):  # an unset quaternion: no rotation
        return (p.x, p.y, p.z), (0.0, 0.0, 0.0)
    return (p.x, p.y, p.z), rpy_from_quaternion_xyzw(q.x, q.y, q.z, q.w)


def _spawn(
    server: WorldServer, name: str, xml: str, robot_namespace: str, pose: Pose, reference: str
) -> tuple[bool, str]:
    if reference not in ("", "world"):
        return False, f"reference_frame '{reference}': only the world frame is supported"
    xyz, rpy = _pose(pose)
    try:
        if "<sdf" in xml[:512]:
            server.spawn_sdf(name or "model", xml, xyz_m=xyz, rpy_rad=rpy)
        else:
            server.spawn(
                name or "robot", xml, xyz_m=xyz, rpy_rad=rpy, robot_namespace=robot_namespace or "/"
            )
    except _ERRORS as exc:
        return False, str(exc)
    return True, "Successfully spawned entity"


def spawn_model(server: WorldServer, request: gz.SpawnModel_Request) -> gz.SpawnModel_Response:
    """gazebo_ros (ROS 1) ``/gazebo/spawn_urdf_model`` and ``/gazebo/spawn_sdf_model``."""
    ok, message = _spawn(
        server, request.model_name, request.model_xml, request.robot_namespace,
        request.initial_pose, request.reference_frame,
    )  # fmt: skip
    return gz.SpawnModel_Response(ok, f"SpawnModel: {message}")


def spawn_entity(server: WorldServer, request: gz.SpawnEntity_Request) -> gz.SpawnEntity_Response:
    """gazebo_ros (ROS 2) ``/spawn_entity``."""
    ok, message = _spawn(
        server, request.name, request.xml, request.robot_namespace,
        request.initial_pose, request.reference_frame,
    )  # fmt: skip
    return gz.SpawnEntity_Response(ok, f"SpawnEntity: {message}")


def _delete(server: WorldServer, name: str) -> tuple[bool, str]:
    try:
        server.delete(name)
    except RobomodelError as exc:
        return False, str(exc)
    return True, "successfully deleted model"


def delete_model(server: WorldServer, request: gz.DeleteModel_Request) -> gz.DeleteModel_Response:
    ok, message = _delete(server, request.model_name)
    return gz.DeleteModel_Response(ok, f"DeleteModel: {message}")


def delete_entity(
    server: WorldServer, request: gz.DeleteEntity_Request
) -> gz.DeleteEntity_Response:
    ok, message = _delete(server, request.name)
    return gz.DeleteEntity_Response(ok, f"DeleteEntity: {message}")


def set_model_configuration(
    server: WorldServer, request: gz.SetModelConfiguration_Request
) -> gz.SetModelConfiguration_Response:
    """gazebo_ros ``/gazebo/set_model_configuration`` (``spawn_model -J``): joint positions."""
    if len(request.joint_names) != len(request.joint_positions):
        return gz.SetModelConfiguration_Response(
            False, "SetModelConfiguration: joint_names and joint_positions differ in length"
        )
    positions = dict(zip(request.joint_names, request.joint_positions, strict=True))
    try:
        server.set_joint_positions(request.model_name, positions)
    except RobomodelError as exc:
        return gz.SetModelConfiguration_Response(False, f"SetModelConfiguration: {exc}")
    return gz.SetModelConfiguration_Response(True, "SetModelConfiguration: success")


def get_world_properties(server: WorldServer, _request: Any) -> gz.GetWorldProperties_Response:
    """gazebo_ros ``/gazebo/get_world_properties``: the sim time and the models' names."""
    return gz.GetWorldProperties_Response(
        sim_time=server.sim.time_s if server.sim is not None else 0.0,
        model_names=server.model_names(),
        rendering_enabled=False,
        success=True,
        status_message="GetWorldProperties: got properties",
    )


def get_model_list(server: WorldServer, _request: Any) -> gz.GetModelList_Response:
    """gazebo_ros (ROS 2) ``/get_model_list``."""
    return gz.GetModelList_Response(Header(), server.model_names(), True)


_ROS2_ONLY = ("/spawn_entity", "/delete_entity", "/get_model_list")


def service_handlers(server: WorldServer) -> list[tuple[str, Any, Handler]]:
    """(name, type, handler) of the server's services, in the order they are offered; ROS 2
    gazebo_ros's root-level names only on a ROS 2 graph."""
    handlers = _handlers(server)
    if server.ros_version == 1:
        return [h for h in handlers if h[0] not in _ROS2_ONLY]
    return handlers


def _handlers(server: WorldServer) -> list[tuple[str, Any, Handler]]:
    return [
        ("/gazebo/spawn_urdf_model", gz.SpawnModel, lambda r: spawn_model(server, r)),
        ("/gazebo/spawn_sdf_model", gz.SpawnModel, lambda r: spawn_model(server, r)),
        ("/spawn_entity", gz.SpawnEntity, lambda r: spawn_entity(server, r)),
        ("/gazebo/delete_model", gz.DeleteModel, lambda r: delete_model(server, r)),
        ("/delete_entity", gz.DeleteEntity, lambda r: delete_entity(server, r)),
        ("/gazebo/set_model_configuration", gz.SetModelConfiguration,
         lambda r: set_model_configuration(server, r)),
        ("/gazebo/get_world_properties", gz.GetWorldProperties,
         lambda r: get_world_properties(server, r)),
        ("/get_model_list", gz.GetModelList, lambda r: get_model_list(server, r)),
    ]  # fmt: skip
