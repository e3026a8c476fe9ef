"""A controller manager offers its services only once it can answer them.

CI saw seed 002's spawner call ``load_controller`` in the moment between the manager's
services appearing and the parameter server being attached as its controller source: both
loads failed with "has no type". The manager now serves after its configuration is set.
"""

from __future__ import annotations

import logging
from typing import Any

from robomodel.control import ControlSystem
from robomodel.control.config import load_controller_config
from robomodel.runtime import Context
from robomodel.xacro import process_file
from tests.conftest import EXAMPLES, importorskip_mujoco

ARM = EXAMPLES / "two_link_arm"
LOAD = "/controller_manager/load_controller"


def _arm() -> Any:
    from robomodel.description import read_urdf

    return read_urdf(process_file(str(ARM / "urdf" / "two_link_arm.urdf.xacro")).toxml()).robot


def test_services_are_offered_after_the_configuration_and_prepare() -> None:
    config = load_controller_config(ARM / "config" / "position_controllers.yaml")
    seen: dict[str, Any] = {}
    with Context("inproc") as ctx:

        def prepare(manager: Any) -> None:  # (inproc: graph()'s timeout_s bounds nothing)
            seen["offered"] = LOAD in ctx.graph(timeout_s=1.0).services
            seen["specs"] = sorted(manager.specs)

        system = ControlSystem.build(_arm(), config, context=ctx, spawn=[], prepare=prepare)
        try:
            assert seen["offered"] is False
            assert seen["specs"] == sorted(c.name for c in config.controllers)
            assert LOAD in ctx.graph(timeout_s=1.0).services
        finally:
            system.manager.shutdown()


def test_a_simulated_robot_s_manager_serves_after_prepare() -> None:
    importorskip_mujoco()
    from robomodel.loading import load
    from robomodel.sim import Simulation

    rrbot = EXAMPLES / "rrbot_description"
    config = load_controller_config(rrbot / "config" / "rrbot_control.yaml")
    seen: dict[str, bool] = {}
    with Context("inproc") as ctx:
        sim = Simulation(world=None)
        sim.add_robot(load(str(rrbot / "urdf" / "rrbot.xacro")))

        def prepare(manager: Any) -> None:  # (inproc: graph()'s timeout_s bounds nothing)
            seen["offered"] = LOAD in ctx.graph(timeout_s=1.0).services
            manager.spec_source = lambda name: None

        system = sim.control(config, context=ctx, spawn=[], prepare=prepare)
        try:
            assert seen == {"offered": False}
            assert system.manager.spec_source is not None
            assert LOAD in ctx.graph(timeout_s=1.0).services
        finally:
            system.manager.shutdown()


def test_a_launch_shows_its_nodes_warnings_and_errors() -> None:
    """roscpp prints ROS_ERROR on the node's terminal, which roslaunch shows: the controller
    manager's reason for refusing a load is in the launch's output, under the node's name."""
    from robomodel.launch.runner import LaunchRunner, RunOptions

    lines: list[str] = []
    runner = LaunchRunner([], RunOptions(bus="inproc", headless=True), log=lines.append)
    runner.open_bus()
    try:
        node = runner.context.create_node("controller_manager", "/arm")
        node.logger.error("Could not load controller '%s'", "bogus")
        node.logger.info("not shown: roslaunch shows a node's info only with output=screen")
    finally:
        runner.shutdown()
    assert "[/arm/controller_manager] [ERROR] Could not load controller 'bogus'" in lines
    assert not any("not shown" in line for line in lines)
    node.logger.error("after the launch")  # the handler went with the launch
    assert not any("after the launch" in line for line in lines)
    assert not logging.getLogger("robomodel.node").handlers
