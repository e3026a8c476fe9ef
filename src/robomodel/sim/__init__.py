"""Simulation: Gazebo's role on MuJoCo (worlds, spawning, physics from the URDF, sensors,
simulated hardware for the controller manager). Needs the ``sim`` extra (``mujoco``)."""

from robomodel.sim.build.robot import BuiltRobot, Placement
from robomodel.sim.engine import Simulation
from robomodel.sim.exceptions import DivergenceError, SimulationError, WorldError
from robomodel.sim.world import World, default_world, parse_world, read_world

__all__ = [
    "BuiltRobot",
    "DivergenceError",
    "Placement",
    "Simulation",
    "SimulationError",
    "World",
    "WorldError",
    "default_world",
    "parse_world",
    "read_world",
]
