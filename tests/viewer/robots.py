"""Small descriptions written by the viewer tests (an arm that sweeps a large screen area)."""

from __future__ import annotations

from pathlib import Path

ARM = """<?xml version="1.0"?>
<robot name="arm">
  <material name="red"><color rgba="0.9 0.1 0.1 1"/></material>
  <link name="base_link">
    <visual><geometry><box size="0.4 0.4 0.2"/></geometry><material name="red"/></visual>
  </link>
  <link name="link1">
    <visual>
      <origin xyz="0 0 0.5"/>
      <geometry><box size="{width} 0.15 1.0"/></geometry>
      <material name="blue"><color rgba="0.1 0.2 0.9 1"/></material>
    </visual>
    <collision><origin xyz="0 0 0.5"/><geometry><cylinder radius="0.25" length="1.0"/></geometry></collision>
  </link>
  <joint name="joint1" type="revolute">
    <parent link="base_link"/><child link="link1"/>
    <origin xyz="0 0 0.1"/><axis xyz="1 0 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
  <link name="tool">
    <visual><geometry><mesh filename="{mesh}" scale="0.2 0.2 0.2"/></geometry></visual>
  </link>
  <joint name="tool_joint" type="fixed">
    <parent link="link1"/><child link="tool"/><origin xyz="0 0 1.1"/>
  </joint>
  {extra}
</robot>
"""


def write_arm(
    directory: Path, *, width: float = 0.15, mesh: str = "cube.stl", extra: str = ""
) -> Path:
    """Write ``arm.urdf`` (and a unit-cube STL) into ``directory``; return the URDF path."""
    import trimesh

    cube = directory / "cube.stl"
    if not cube.exists():
        trimesh.creation.box(extents=(1.0, 1.0, 1.0)).export(cube)
    path = directory / "arm.urdf"
    path.write_text(ARM.format(width=width, mesh=mesh, extra=extra))
    return path
