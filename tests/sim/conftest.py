"""Shared paths and builders for the simulator tests (skipped without MuJoCo)."""

from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("mujoco")

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
RRBOT = EXAMPLES / "rrbot_description/urdf/rrbot.xacro"
RRBOT_YAML = EXAMPLES / "rrbot_description/config/rrbot_control.yaml"
UR5 = EXAMPLES / "ur5_description/urdf/ur5.urdf.xacro"
UR5_YAML = EXAMPLES / "ur5_description/config/ur5_controllers.yaml"
SIMPLEBOT = EXAMPLES / "simplebot_description/urdf/simplebot.urdf.xacro"
SIMPLEBOT_LIDAR = EXAMPLES / "simplebot_description/urdf/simplebot_lidar.urdf.xacro"
SIMPLEBOT_CAMERA = EXAMPLES / "simplebot_description/urdf/simplebot_camera.urdf.xacro"
SIMPLEBOT_YAML = EXAMPLES / "simplebot_description/config/simplebot_controllers.yaml"
WALL_WORLD = EXAMPLES / "simplebot_description/worlds/wall.world"
