"""Benchmark robomodel.xacro against the reference xacro 2.1.1, in one process.

For each input, both processors expand the file (from disk, as their CLIs do) and print it with
``toprettyxml(indent="  ")``; the bytes must be identical. Prints the median wall time per run of
each, and the median of the per-run ratios (the two run alternately).

Inputs:
  * the biggest example (``examples/ur5_description`` joint-limited UR5),
  * a synthetic PR2-size robot generated into a temporary directory (>= 80 links through macros,
    four include levels, > 130 kB of URDF),
  * optionally the PR2 snapshot shipped in the reference's sdist (``--pr2 DIR`` = the unpacked
    ``xacro-2.1.1`` directory, whose ``test/robots/pr2`` uses ``$(find xacro)``).

With ``--scaling`` only serial chains of 10, 100 and 1,000 links (one macro call per link) are
run, for BENCHMARKS.md's scaling table.

Usage:
    python bench/bench_xacro.py [--runs N] [--pr2 DIR] [--scaling]
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import io
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from robomodel import xacro as rx
from robomodel.description.packages import PackageIndex

REPO = Path(__file__).resolve().parents[1]

COMMON = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="M_PI" value="3.1415926535897931"/>
  <xacro:property name="default_mass" value="1.5"/>
  <xacro:include filename="$(find synth_description)/urdf/common/materials.xacro"/>
  <xacro:macro name="cyl_inertia" params="m r h">
    <inertial>
      <mass value="${m}"/>
      <origin xyz="0 0 ${h/2}" rpy="0 0 0"/>
      <inertia ixx="${m*(3*r*r+h*h)/12}" ixy="0" ixz="0" iyy="${m*(3*r*r+h*h)/12}" iyz="0" izz="${m*r*r/2}"/>
    </inertial>
  </xacro:macro>
  <!-- A link with visual, collision, inertia and its Gazebo block -->
  <xacro:macro name="part" params="name r:=0.05 h:=0.2 m:=${default_mass} color:=Grey">
    <link name="${name}">
      <visual>
        <origin xyz="0 0 ${h/2}" rpy="0 0 0"/>
        <geometry>
          <cylinder radius="${r}" length="${h}"/>
        </geometry>
        <material name="${color}"/>
      </visual>
      <collision>
        <origin xyz="0 0 ${h/2}" rpy="0 0 0"/>
        <geometry>
          <cylinder radius="${r*1.05}" length="${h}"/>
        </geometry>
      </collision>
      <xacro:cyl_inertia m="${m}" r="${r}" h="${h}"/>
    </link>
    <gazebo reference="${name}">
      <material>Gazebo/${color}</material>
      <mu1>0.9</mu1>
      <mu2>0.9</mu2>
      <selfCollide>false</selfCollide>
    </gazebo>
  </xacro:macro>
  <xacro:macro name="rev_joint" params="name parent child axis:='0 0 1' lower:=${-M_PI} upper:=${M_PI} *origin">
    <joint name="${name}" type="revolute">
      <parent link="${parent}"/>
      <child link="${child}"/>
      <xacro:insert_block name="origin"/>
      <axis xyz="${axis}"/>
      <limit lower="${lower}" upper="${upper}" effort="30" velocity="${M_PI/2}"/>
      <dynamics damping="0.1" friction="0.01"/>
      <safety_controller k_position="100" k_velocity="10" soft_lower_limit="${lower + 0.1}" soft_upper_limit="${upper - 0.1}"/>
    </joint>
    <transmission name="${name}_trans">
      <type>transmission_interface/SimpleTransmission</type>
      <joint name="${name}">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
      </joint>
      <actuator name="${name}_motor">
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>
        <mechanicalReduction>${1 + len(name) % 7}</mechanicalReduction>
      </actuator>
    </transmission>
  </xacro:macro>
</robot>
"""

MATERIALS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="material" params="name rgba">
    <material name="${name}">
      <color rgba="${rgba}"/>
    </material>
  </xacro:macro>
  <xacro:material name="Grey" rgba="0.7 0.7 0.7 1.0"/>
  <xacro:material name="Blue" rgba="0.0 0.0 0.8 1.0"/>
  <xacro:material name="Red" rgba="0.8 0.0 0.0 1.0"/>
  <xacro:material name="White" rgba="1.0 1.0 1.0 1.0"/>
</robot>
"""

ARM = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="gripper.xacro"/>
  <!-- A chain of n segments, built recursively -->
  <xacro:macro name="segment" params="side i n parent">
    <xacro:part name="${side}_link_${i}" r="${0.06 - 0.004*i}" h="${0.3 - 0.02*i}" color="${'Blue' if i % 2 else 'Grey'}"/>
    <xacro:rev_joint name="${side}_joint_${i}" parent="${parent}" child="${side}_link_${i}" axis="${'0 0 1' if i % 2 else '0 1 0'}">
      <origin xyz="0 0 ${0.3 - 0.02*(i-1) if i > 1 else 0.1}" rpy="0 0 0"/>
    </xacro:rev_joint>
    <xacro:if value="${i &lt; n}">
      <xacro:segment side="${side}" i="${i+1}" n="${n}" parent="${side}_link_${i}"/>
    </xacro:if>
  </xacro:macro>
  <xacro:macro name="arm" params="side reflect n:=9">
    <xacro:segment side="${side}" i="1" n="${n}" parent="${side}_shoulder_mount"/>
    <link name="${side}_shoulder_mount"/>
    <joint name="${side}_shoulder_mount_joint" type="fixed">
      <parent link="torso_link"/>
      <child link="${side}_shoulder_mount"/>
      <origin xyz="0 ${reflect*0.188} 0.7" rpy="0 0 0"/>
    </joint>
    <xacro:gripper side="${side}" parent="${side}_link_${n}"/>
  </xacro:macro>
</robot>
"""

GRIPPER = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="finger" params="side name parent reflect">
    <xacro:part name="${side}_${name}_finger" r="0.01" h="0.05" m="0.1" color="White"/>
    <xacro:rev_joint name="${side}_${name}_finger_joint" parent="${parent}" child="${side}_${name}_finger" lower="0" upper="0.55">
      <origin xyz="0.05 ${reflect*0.01} 0" rpy="0 0 0"/>
    </xacro:rev_joint>
    <xacro:part name="${side}_${name}_tip" r="0.008" h="0.04" m="0.05" color="White"/>
    <xacro:rev_joint name="${side}_${name}_tip_joint" parent="${side}_${name}_finger" child="${side}_${name}_tip" lower="0" upper="0.55">
      <origin xyz="0.05 0 0" rpy="0 0 0"/>
    </xacro:rev_joint>
  </xacro:macro>
  <xacro:macro name="gripper" params="side parent">
    <xacro:part name="${side}_palm" r="0.04" h="0.08" m="0.6" color="Red"/>
    <joint name="${side}_palm_joint" type="fixed">
      <parent link="${parent}"/>
      <child link="${side}_palm"/>
      <origin xyz="0 0 0.12" rpy="0 0 0"/>
    </joint>
    <xacro:finger side="${side}" name="l" parent="${side}_palm" reflect="1"/>
    <xacro:finger side="${side}" name="r" parent="${side}_palm" reflect="-1"/>
  </xacro:macro>
</robot>
"""

BASE = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="caster" params="name x y">
    <xacro:part name="${name}_rotation_link" r="0.03" h="0.07" m="3.5"/>
    <xacro:rev_joint name="${name}_rotation_joint" parent="base_link" child="${name}_rotation_link">
      <origin xyz="${x} ${y} 0.0282" rpy="0 0 0"/>
    </xacro:rev_joint>
    <xacro:property name="wheels" value="${['l', 'r']}"/>
    <xacro:part name="${name}_${wheels[0]}_wheel_link" r="0.074792" h="0.034" m="0.44036" color="Blue"/>
    <xacro:rev_joint name="${name}_${wheels[0]}_wheel_joint" parent="${name}_rotation_link" child="${name}_${wheels[0]}_wheel_link" axis="0 1 0">
      <origin xyz="0 0.049 0" rpy="0 0 0"/>
    </xacro:rev_joint>
    <xacro:part name="${name}_${wheels[1]}_wheel_link" r="0.074792" h="0.034" m="0.44036" color="Blue"/>
    <xacro:rev_joint name="${name}_${wheels[1]}_wheel_joint" parent="${name}_rotation_link" child="${name}_${wheels[1]}_wheel_link" axis="0 1 0">
      <origin xyz="0 -0.049 0" rpy="0 0 0"/>
    </xacro:rev_joint>
  </xacro:macro>
  <xacro:macro name="camera" params="name parent z">
    <xacro:part name="${name}_link" r="0.02" h="0.03" m="0.1" color="Red"/>
    <joint name="${name}_joint" type="fixed">
      <parent link="${parent}"/>
      <child link="${name}_link"/>
      <origin xyz="0.1 0 ${z}" rpy="0 0 0"/>
    </joint>
    <link name="${name}_optical_frame"/>
    <joint name="${name}_optical_joint" type="fixed">
      <parent link="${name}_link"/>
      <child link="${name}_optical_frame"/>
      <origin xyz="0 0 0" rpy="${-M_PI/2} 0 ${-M_PI/2}"/>
    </joint>
    <gazebo reference="${name}_link">
      <sensor type="camera" name="${name}_sensor">
        <update_rate>30.0</update_rate>
        <camera name="${name}">
          <horizontal_fov>${90 * M_PI / 180}</horizontal_fov>
          <image>
            <width>640</width>
            <height>480</height>
            <format>R8G8B8</format>
          </image>
          <clip>
            <near>0.02</near>
            <far>300</far>
          </clip>
        </camera>
      </sensor>
    </gazebo>
  </xacro:macro>
</robot>
"""

TOP = """<?xml version="1.0"?>
<robot name="synth_pr2" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="arm_segments" default="10"/>
  <xacro:include filename="$(find synth_description)/urdf/common/common.xacro"/>
  <xacro:include filename="$(find synth_description)/urdf/base/base.xacro"/>
  <xacro:include filename="$(find synth_description)/urdf/arm/arm.xacro"/>
  <link name="base_footprint"/>
  <xacro:part name="base_link" r="0.33" h="0.3" m="116.0"/>
  <joint name="base_footprint_joint" type="fixed">
    <parent link="base_footprint"/>
    <child link="base_link"/>
    <origin xyz="0 0 0.051" rpy="0 0 0"/>
  </joint>
  <xacro:caster name="fl_caster" x="0.2246" y="0.2246"/>
  <xacro:caster name="fr_caster" x="0.2246" y="-0.2246"/>
  <xacro:caster name="bl_caster" x="-0.2246" y="0.2246"/>
  <xacro:caster name="br_caster" x="-0.2246" y="-0.2246"/>
  <xacro:part name="torso_link" r="0.1" h="0.8" m="36.4"/>
  <xacro:rev_joint name="torso_joint" parent="base_link" child="torso_link" lower="0" upper="0.33">
    <origin xyz="-0.05 0 0.739675" rpy="0 0 0"/>
  </xacro:rev_joint>
  <xacro:part name="head_pan_link" r="0.05" h="0.1" m="6.3"/>
  <xacro:rev_joint name="head_pan_joint" parent="torso_link" child="head_pan_link">
    <origin xyz="-0.017 0 0.38145" rpy="0 0 0"/>
  </xacro:rev_joint>
  <xacro:part name="head_tilt_link" r="0.05" h="0.1" m="1.7"/>
  <xacro:rev_joint name="head_tilt_joint" parent="head_pan_link" child="head_tilt_link" axis="0 1 0">
    <origin xyz="0.068 0 0" rpy="0 0 0"/>
  </xacro:rev_joint>
  <xacro:arm side="left" reflect="1" n="$(arg arm_segments)"/>
  <xacro:arm side="right" reflect="-1" n="$(arg arm_segments)"/>
  <xacro:arm side="aux_left" reflect="0.5" n="6"/>
  <xacro:arm side="aux_right" reflect="-0.5" n="6"/>
  <xacro:camera name="wide_stereo_l" parent="head_tilt_link" z="0.05"/>
  <xacro:camera name="wide_stereo_r" parent="head_tilt_link" z="0.06"/>
  <xacro:camera name="narrow_stereo_l" parent="head_tilt_link" z="0.07"/>
  <xacro:camera name="narrow_stereo_r" parent="head_tilt_link" z="0.08"/>
  <xacro:camera name="forearm_l" parent="left_link_5" z="0.1"/>
  <xacro:camera name="forearm_r" parent="right_link_5" z="0.1"/>
  <xacro:camera name="aux_forearm_l" parent="aux_left_link_5" z="0.1"/>
  <xacro:camera name="aux_forearm_r" parent="aux_right_link_5" z="0.1"/>
  <xacro:camera name="base_front" parent="base_link" z="0.2"/>
  <xacro:camera name="base_rear" parent="base_link" z="0.25"/>
  <xacro:camera name="tool_l" parent="left_palm" z="0.05"/>
  <xacro:camera name="tool_r" parent="right_palm" z="0.05"/>
</robot>
"""

FILES = {
    "package.xml": '<?xml version="1.0"?>\n<package format="3"><name>synth_description</name>'
    "<version>0.0.0</version><description>synthetic</description>"
    '<maintainer email="a@b.c">a</maintainer><license>BSD</license></package>\n',
    "urdf/common/common.xacro": COMMON,
    "urdf/common/materials.xacro": MATERIALS,
    "urdf/arm/arm.xacro": ARM,
    "urdf/arm/gripper.xacro": GRIPPER,
    "urdf/base/base.xacro": BASE,
    "urdf/synth_pr2.urdf.xacro": TOP,
}


def chain_xacro(n_links: int) -> str:
    """A serial chain of ``n_links`` links (BENCHMARKS.md's scaling table): one macro call per link,
    each with an inertial, a box visual and a cylinder collision, computed from properties."""
    calls = "\n".join(
        f'  <xacro:segment i="{i}" parent="link_{i - 1}"/>' for i in range(1, n_links)
    )
    return f"""<?xml version="1.0"?>
<robot name="chain{n_links}" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="length" value="0.1"/>
  <xacro:property name="radius" value="0.02"/>
  <xacro:macro name="segment" params="i parent">
    <link name="link_${{i}}">
      <inertial>
        <origin xyz="0 0 ${{length / 2}}"/>
        <mass value="${{0.5 + 0.001 * i}}"/>
        <inertia ixx="${{0.5 * radius * radius}}" ixy="0" ixz="0" iyy="${{length * length / 12}}"
                 iyz="0" izz="${{length * length / 12}}"/>
      </inertial>
      <visual>
        <origin xyz="0 0 ${{length / 2}}"/>
        <geometry><box size="${{radius}} ${{radius}} ${{length}}"/></geometry>
      </visual>
      <collision>
        <origin xyz="0 0 ${{length / 2}}"/>
        <geometry><cylinder radius="${{radius}}" length="${{length}}"/></geometry>
      </collision>
    </link>
    <joint name="joint_${{i}}" type="revolute">
      <parent link="${{parent}}"/>
      <child link="link_${{i}}"/>
      <origin xyz="0 0 ${{length}}" rpy="0 0 0"/>
      <axis xyz="0 1 0"/>
      <limit lower="${{-pi / 2}}" upper="${{pi / 2}}" effort="10" velocity="1"/>
    </joint>
  </xacro:macro>
  <link name="link_0"/>
{calls}
</robot>
"""


def write_synthetic_robot(root: Path) -> Path:
    """Write the synthetic PR2-size package below ``root``; return the top xacro file."""
    for relative, text in FILES.items():
        path = root / "synth_description" / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root / "synth_description" / "urdf" / "synth_pr2.urdf.xacro"


def _reference_runner(path: Path, index: PackageIndex) -> Callable[[], str]:
    import xacro
    import xacro.substitution_args as substitution_args  # type: ignore[import-untyped]

    substitution_args._eval_find = lambda pkg: str(index.find(pkg))

    def run() -> str:
        xacro.all_includes = []
        xacro.init_stacks(None)
        with contextlib.redirect_stderr(io.StringIO()):
            doc = xacro.process_file(str(path), mappings={})
        return str(doc.toprettyxml(indent="  "))

    return run


def _ours_runner(path: Path, index: PackageIndex) -> Callable[[], str]:
    def run() -> str:
        return rx.process_file(path, package_index=index).toprettyxml(indent="  ")

    return run


def _time_ms(run: Callable[[], str]) -> float:
    gc.collect()  # each run starts from a clean heap, not with the other's garbage
    start = time.perf_counter()
    run()
    return (time.perf_counter() - start) * 1000


def bench(label: str, path: Path, index: PackageIndex, runs: int) -> bool:
    """Benchmark one input; return whether the outputs are identical.

    The two processors run alternately, so that a change of machine load affects both alike;
    the ratio reported is the median of the per-pair ratios.
    """
    reference, ours = _reference_runner(path, index), _ours_runner(path, index)
    expected, actual = reference(), ours()  # warm-up, and the byte check
    identical = expected == actual
    links = actual.count("<link ")
    ref_times, our_times = [], []
    for _ in range(runs):
        ref_times.append(_time_ms(reference))
        our_times.append(_time_ms(ours))
    ratio = statistics.median(r / o for r, o in zip(ref_times, our_times, strict=True))
    ref_ms, our_ms = statistics.median(ref_times), statistics.median(our_times)
    print(
        f"{label:<28} {len(actual) / 1024:7.1f} KiB {links:4d} links | reference {ref_ms:8.2f} ms"
        f" | robomodel {our_ms:7.2f} ms | {ratio:5.1f}x | "
        f"{'identical bytes' if identical else 'OUTPUT DIFFERS'}"
    )
    return identical


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--runs", type=int, default=30, help="timed runs per processor")
    parser.add_argument(
        "--pr2", type=Path, help="unpacked xacro-2.1.1 sdist (for its PR2 snapshot)"
    )
    parser.add_argument(
        "--scaling",
        action="store_true",
        help="only the synthetic chains of 10, 100 and 1,000 links (BENCHMARKS.md's scaling table)",
    )
    args = parser.parse_args(argv)
    print(f"Python {sys.version.split()[0]}, median of {args.runs} runs, in one process")
    ok = True
    if args.scaling:
        no_packages = PackageIndex(use_environment=False)
        with tempfile.TemporaryDirectory() as tmp:
            for n_links in (10, 100, 1000):
                path = Path(tmp) / f"chain{n_links}.urdf.xacro"
                path.write_text(chain_xacro(n_links))
                ok &= bench(f"chain of {n_links} links", path, no_packages, args.runs)
        return 0 if ok else 1
    examples = PackageIndex(package_paths=[REPO / "examples"], use_environment=False)
    biggest = REPO / "examples/ur5_description/urdf/ur5_joint_limited_robot.urdf.xacro"
    ok &= bench("example: UR5 joint-limited", biggest, examples, args.runs)
    with tempfile.TemporaryDirectory() as tmp:
        top = write_synthetic_robot(Path(tmp))
        index = PackageIndex(package_paths=[tmp], use_environment=False)
        ok &= bench("synthetic PR2-size robot", top, index, args.runs)
    if args.pr2:
        index = PackageIndex(packages={"xacro": args.pr2}, use_environment=False)
        ok &= bench(
            "PR2 (xacro sdist snapshot)",
            args.pr2 / "test/robots/pr2/pr2.urdf.xacro",
            index,
            args.runs,
        )
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
