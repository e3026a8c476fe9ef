"""Seed 000, "Robot Modelling and Control in ROS": gripper_description (planar_3dof URDF,
check_urdf, display.launch, rosparam, xacro, joint/robot state publishers, tf) and the rrbot
ros_control packages (YAML, rrbot_control.launch, two terminals, rostopic pub, the controller
manager's commands), as the student types them.

The seed's file text is copied below; only its typos are fixed, each fix named in a comment.
Where the seed shows a fragment and tells the student to write the rest ("Add two links ... and
two joints"), the rest follows its instructions and says so.
"""

from __future__ import annotations

import shutil
import signal
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.conftest import EXAMPLES, ROBOMODEL, debian_check_urdf
from tests.seeds.conftest import (
    MASTERS,
    ROSNODE,
    ROSPARAM,
    ROSSERVICE,
    ROSTOPIC,
    SeedRos1,
    box_stl,
    joint_position,
    package_xml,
    start_master,
    until,
    write_tree,
)
from tests.timing import scaled

# --- the seed's files -----------------------------------------------------------------------

# "First URDF model": the seed's link_1 and joint_1 fragments; link_2, gripper, joint_2 and
# joint_3 are the student's ("Add two links (link_2 and gripper) and two joints (joint_2 and
# joint_3)"), written the same way with the links' 0.5 m.
_LINK = """<link name="{name}">
<visual>
<geometry>
<mesh filename="package://gripper_description/meshes/visual/{mesh}.stl" />
<material name="grey"> <color rgba="0.7 0.7 0.7 1.0" /> </material>
</geometry>
</visual>
<collision><geometry>
<mesh
filename="package://gripper_description/meshes/collision/{mesh}.stl" />
</geometry></collision>
</link>
"""
# typo fixed: the seed's <parent link="base_link"> is not closed (<parent link="base_link"/>)
_JOINT = """<joint name="{name}" type="revolute">
<parent link="{parent}"/> <child link="{child}" />
<origin xyz="{x} 0 0" rpy="0 0 0" /> <axis xyz="0 0 1" />
<limit lower="-1.57" upper="1.57" effort="0" velocity="0.5" /></joint>
"""
PLANAR_3DOF_URDF = (
    '<robot name="planar_3dof">\n<link name="base_link" />\n'
    + _LINK.format(name="link_1", mesh="arm_link")
    + _JOINT.format(name="joint_1", parent="base_link", child="link_1", x="0")
    + _LINK.format(name="link_2", mesh="arm_link")
    + _JOINT.format(name="joint_2", parent="link_1", child="link_2", x="0.5")
    + _LINK.format(name="gripper", mesh="gripper_link")
    + _JOINT.format(name="joint_3", parent="link_2", child="gripper", x="0.5")
    + "</robot>\n"
)

# "Testing URDF in Rviz": display.launch as the seed shows it
DISPLAY_LAUNCH = """<launch>
<param name="robot_description" textfile="$(find gripper_description)/urdf/planar_3dof.urdf"/>
<node name="joint_state_publisher" pkg="joint_state_publisher" type="joint_state_publisher" />
<node name="robot_state_publisher" pkg="robot_state_publisher" type="state_publisher" />
<node name="rviz" pkg="rviz" type="rviz" args="-d $(find gripper_description)/urdf/urdf.rviz"
  required="true"/>
</launch>
"""

# What RViz 1.14 writes with "Save Config" after the seed's three steps (RobotModel and TF
# added, Fixed Frame = base_link): the file the student stores as urdf/urdf.rviz.
URDF_RVIZ = """Panels:
  - Class: rviz/Displays
    Name: Displays
Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz/Grid
      Enabled: true
      Name: Grid
    - Class: rviz/RobotModel
      Enabled: true
      Name: RobotModel
      Robot Description: robot_description
    - Class: rviz/TF
      Enabled: true
      Name: TF
  Enabled: true
  Global Options:
    Background Color: 48; 48; 48
    Fixed Frame: base_link
    Frame Rate: 30
  Name: root
  Views:
    Current:
      Class: rviz/Orbit
      Distance: 3
      Name: Current View
"""

# "URDF simplification with xacro": the student's planar_3dof.xacro from the seed's pieces
# (properties pi, link_length, base_height, vel_max; a link macro with link_name, visual_mesh and
# collision_mesh). Typos fixed: the seed's "$(math -pi/2.0)" / "$(math pi/2.0)" are its
# rendering of "${-pi/2.0}" / "${pi/2.0}" (the text says "Use of the property with
# ${property_name}").
PLANAR_3DOF_XACRO = """<?xml version="1.0"?>
<robot name="planar_3dof" xmlns:xacro="http://www.ros.org/wiki/xacro">
<xacro:property name="pi" value="3.1415926535897931" />
<xacro:property name="link_length" value="0.5" />
<xacro:property name="base_height" value="0.1" />
<xacro:property name="vel_max" value="0.5" />
<xacro:macro name="arm_link" params="link_name visual_mesh collision_mesh">
<link name="${link_name}">
<visual>
<geometry>
<mesh filename="package://gripper_description/meshes/visual/${visual_mesh}" />
</geometry>
<material name="grey"> <color rgba="0.7 0.7 0.7 1.0" /> </material>
</visual>
<collision><geometry>
<mesh filename="package://gripper_description/meshes/collision/${collision_mesh}" />
</geometry></collision>
</link>
</xacro:macro>
<link name="base_link" />
<xacro:arm_link link_name="link_1" visual_mesh="arm_link.stl" collision_mesh="arm_link.stl" />
<xacro:arm_link link_name="link_2" visual_mesh="arm_link.stl" collision_mesh="arm_link.stl" />
<xacro:arm_link link_name="gripper" visual_mesh="gripper_link.stl" collision_mesh="gripper_link.stl" />
<joint name="joint_1" type="revolute">
<parent link="base_link"/> <child link="link_1" />
<origin xyz="0 0 0" rpy="0 0 0" /> <axis xyz="0 0 1" />
<limit lower="${-pi/2.0}" upper="${pi/2.0}" effort="0" velocity="${vel_max}" /></joint>
<joint name="joint_2" type="revolute">
<parent link="link_1"/> <child link="link_2" />
<origin xyz="${link_length} 0 0" rpy="0 0 0" /> <axis xyz="0 0 1" />
<limit lower="${-pi/2.0}" upper="${pi/2.0}" effort="0" velocity="${vel_max}" /></joint>
<joint name="joint_3" type="revolute">
<parent link="link_2"/> <child link="gripper" />
<origin xyz="${link_length} 0 0" rpy="0 0 0" /> <axis xyz="0 0 1" />
<limit lower="${-pi/2.0}" upper="${pi/2.0}" effort="0" velocity="${vel_max}" /></joint>
</robot>
"""

# display_xacro.launch as the seed shows it, with the seed's use_gui line ("define the
# parameter use_gui as true by adding this line in the launch file")
DISPLAY_XACRO_LAUNCH = """<launch>
<param name="robot_description" command="$(find xacro)/xacro.py '$(find gripper_description)/urdf/planar_3dof.xacro'" />
<param name="use_gui" value="true" />
<node name="joint_state_publisher" pkg="joint_state_publisher" type="joint_state_publisher" />
<node name="robot_state_publisher" pkg="robot_state_publisher" type="state_publisher" />
<node name="rviz" pkg="rviz" type="rviz" args="-d $(find gripper_description)/urdf/urdf.rviz"
required="true" />
</launch>
"""

# rrbot_control.yaml as the seed shows it. Fixed: the seed's "..." stands for the second
# controller, written as the first one for joint2. Kept: "I: 0.01" (ROS reads "i"; the capital
# is the seed's and is ignored by both).
RRBOT_CONTROL_YAML = """rrbot:
  # Publish all joint states
  joint_state_controller:
    type: joint_state_controller/JointStateController
    publish_rate: 50
  # Position controllers
  joint1_position_controller:
    type: effort_controllers/JointPositionController
    joint: joint1
    pid: {p: 100.0, I: 0.01, d: 10.0}
  joint2_position_controller:
    type: effort_controllers/JointPositionController
    joint: joint2
    pid: {p: 100.0, I: 0.01, d: 10.0}
"""

# rrbot_control.launch as the seed shows it. Typo fixed: the seed closes the
# robot_state_publisher node twice ("respawn="false" output="screen"/>" then "</node>"); the
# <remap> belongs inside it.
RRBOT_CONTROL_LAUNCH = """<launch>
  <rosparam file="$(find rrbot_control)/config/rrbot_control.yaml" command="load"/>

  <node name="controller_spawner" pkg="controller_manager" type="spawner"
    respawn="false" output="screen" ns="/rrbot" args="joint_state_controller
    joint1_position_controller joint2_position_controller" />

  <node name="robot_state_publisher" pkg="robot_state_publisher"
    type="robot_state_publisher" respawn="false" output="screen">
  <remap from="/joint_states" to="/rrbot/joint_states" /> </node>
</launch>
"""


COURSE_DEPENDENCIES = ("roscpp", "tf", "geometry_msgs", "urdf", "rviz", "xacro")


def gripper_description(src: Path, *, with_rviz: bool) -> Path:
    """``catkin_create_pkg gripper_description roscpp tf geometry_msgs urdf rviz xacro`` as
    ``robomodel new`` writes it (the course's line, typed as written), then the provided
    meshes and the seed's files."""
    from robomodel.cli.main import main

    if not (src / "gripper_description").exists():
        assert main(["new", "gripper_description", *COURSE_DEPENDENCIES, "--dir", str(src)]) == 0
    files: dict[str, str | bytes] = {
        "urdf/planar_3dof.urdf": PLANAR_3DOF_URDF,
        "urdf/planar_3dof.xacro": PLANAR_3DOF_XACRO,
        "launch/display.launch": DISPLAY_LAUNCH,
        "launch/display_xacro.launch": DISPLAY_XACRO_LAUNCH,
    }
    for kind in ("visual", "collision"):
        files[f"meshes/{kind}/arm_link.stl"] = box_stl((0.5, 0.06, 0.04))
        files[f"meshes/{kind}/gripper_link.stl"] = box_stl((0.04, 0.16, 0.04))
    if with_rviz:
        files["urdf/urdf.rviz"] = URDF_RVIZ
    return write_tree(src / "gripper_description", files)


def rrbot_packages(src: Path) -> None:
    """The seed's three RRBot packages: rrbot_description and rrbot_gazebo are gazebo_ros_demos'
    (the seed shows fragments of them; examples/ holds the whole files), rrbot_control is the
    seed's own text."""
    for name in ("rrbot_description", "rrbot_gazebo"):
        shutil.copytree(EXAMPLES / name, src / name)
    write_tree(
        src / "rrbot_control",
        {
            "package.xml": package_xml("rrbot_control"),
            "config/rrbot_control.yaml": RRBOT_CONTROL_YAML,
            "launch/rrbot_control.launch": RRBOT_CONTROL_LAUNCH,
        },
    )


@pytest.fixture
def graph(ros1_graph: SeedRos1) -> SeedRos1:
    return ros1_graph


def _src(graph: SeedRos1) -> Path:
    return Path(graph.packages)


# --- "Testing URDF with commands" -----------------------------------------------------------


def test_check_urdf_prints_what_the_seed_shows(graph: SeedRos1) -> None:
    """``check_urdf planar_3dof.urdf`` → ``robomodel check planar_3dof.urdf``: the seed's output,
    and the same lines as Debian's check_urdf."""
    urdf = gripper_description(_src(graph), with_rviz=False) / "urdf"
    ours = graph.tool(*ROBOMODEL, "check", "planar_3dof.urdf", cwd=urdf)
    assert ours.returncode == 0, ours.stderr
    lines = [line.strip() for line in ours.stdout.splitlines()]
    assert lines[0] == "robot name is: planar_3dof"
    assert "Successfully Parsed XML" in lines[1]
    assert lines[2:] == [
        "root Link: base_link has 1 child(ren)",
        "child(1):  link_1",
        "child(1):  link_2",
        "child(1):  gripper",
    ]
    reference = graph.tool(debian_check_urdf(), "planar_3dof.urdf", cwd=urdf)
    assert reference.returncode == 0 and ours.stdout == reference.stdout


def test_urdf_to_graphviz_writes_the_pdf(graph: SeedRos1) -> None:
    """``urdf_to_graphviz planar_3dof.urdf`` → ``robomodel graph planar_3dof.urdf``: the same
    planar_3dof.gv and planar_3dof.pdf (the seed then opens planar_3dof.pdf)."""
    if shutil.which("dot") is None:
        pytest.skip("Graphviz's dot renders the pdf")
    urdf = gripper_description(_src(graph), with_rviz=False) / "urdf"
    run = graph.tool(*ROBOMODEL, "graph", "planar_3dof.urdf", cwd=urdf)
    assert run.returncode == 0, run.stderr
    assert run.stdout == "Created file planar_3dof.gv\nCreated file planar_3dof.pdf\n"
    assert (urdf / "planar_3dof.gv").read_text().startswith("digraph G {")
    assert (urdf / "planar_3dof.pdf").read_bytes().startswith(b"%PDF")


# --- "Testing URDF in Rviz" -----------------------------------------------------------------


def test_first_display_launch_runs_before_urdf_rviz_exists(graph: SeedRos1, tmp_path: Path) -> None:
    """ "Firstly, rviz config file (urdf.rviz) is not available": the launch keeps running."""
    gripper_description(_src(graph), with_rviz=False)
    log = tmp_path / "display.log"
    proc = graph.launch(
        log, "gripper_description", "display.launch", "--ros1-master", wait_for="nodes running"
    )
    assert graph.echo("/joint_states")["name"] == ["joint_1", "joint_2", "joint_3"]
    assert proc.poll() is None, log.read_text()


@pytest.mark.parametrize("master", MASTERS)
def test_display_launch_publishes_state_and_tf(
    graph: SeedRos1, tmp_path: Path, master: str
) -> None:
    """With urdf.rviz saved: the launch loads robot_description, joint_state_publisher publishes
    every non-fixed joint, robot_state_publisher the transforms (``roslaunch tf tf_echo
    base_link gripper`` → ``robomodel tf base_link gripper``: two 0.5 m links)."""
    start_master(graph, master)
    gripper_description(_src(graph), with_rviz=True)
    graph.launch(
        tmp_path / "display.log", "gripper_description", "display.launch", "--ros1-master",
        wait_for="nodes running",
    )  # fmt: skip
    # typo fixed: the seed's "rostopic echo /jointstates" is /joint_states
    states = graph.echo("/joint_states")
    assert states["name"] == ["joint_1", "joint_2", "joint_3"]
    assert states["position"] == [0.0, 0.0, 0.0]
    nodes = graph.tool(ROSNODE, "list").stdout.split()
    # the viewer stands for rviz: headless, there is none
    assert {"/joint_state_publisher", "/robot_state_publisher"} <= set(nodes)
    tf = graph.tool(
        *ROBOMODEL, "tf", "base_link", "gripper", "--once", "--timeout", f"{scaled(60):.1f}"
    )
    assert tf.returncode == 0, tf.stderr
    assert "[1.000, 0.000, 0.000]" in tf.stdout


DISPLAY = pytest.mark.xdist_group("seed_000_display")
"""The tests of the shared display.launch: one worker starts it once."""


@pytest.fixture(scope="module")
def display_launch(
    tmp_path_factory: pytest.TempPathFactory,
) -> Iterator[tuple[SeedRos1, Path, dict[str, Any]]]:
    """One display.launch (urdf.rviz saved) hosting the master, for the tests that look at it
    or work on its parameter server (each starting its own took most of their time): the
    graph, the package's urdf folder and the parameter tree the launch left."""
    home = tmp_path_factory.mktemp("display")
    workspace = home / "catkin_ws" / "src"
    workspace.mkdir(parents=True)
    shared = SeedRos1(home, packages=str(workspace))
    try:
        urdf_dir = gripper_description(workspace, with_rviz=True) / "urdf"
        shared.launch(
            home / "display.log", "gripper_description", "display.launch", "--ros1-master",
            wait_for="nodes running",
        )  # fmt: skip
        with shared.master() as master:
            code, message, tree = master.getParam("/test", "/")
        assert code == 1, message
        yield shared, urdf_dir, tree
    finally:
        shared.close()


@pytest.fixture
def display(
    display_launch: tuple[SeedRos1, Path, dict[str, Any]],
) -> Iterator[tuple[SeedRos1, Path]]:
    """The shared display.launch and its urdf folder; the parameters a test set, deleted or
    changed are put back as the launch left them, and the files it wrote there removed."""
    graph, urdf_dir, tree = display_launch
    files = set(urdf_dir.iterdir())
    yield graph, urdf_dir
    with graph.master() as master:
        code, message, now = master.getParam("/test", "/")
        assert code == 1, message
        for name in now.keys() - tree.keys():
            master.deleteParam("/test", f"/{name}")
        for name, value in tree.items():
            master.setParam("/test", f"/{name}", value)
        code, message, now = master.getParam("/test", "/")
    assert now == tree, "the parameter server is not as the launch left it"
    for path in set(urdf_dir.iterdir()) - files:
        path.unlink()


@DISPLAY
def test_view_frames_draws_the_tree(display: tuple[SeedRos1, Path], tmp_path: Path) -> None:
    """ "Tree of tf: ``roslaunch tf view_frames``" (rosrun's job) → ``robomodel run tf
    view_frames``: tf's lines, frames.gv with robot_state_publisher's three edges, frames.pdf."""
    if shutil.which("dot") is None:
        pytest.skip("Graphviz's dot renders the pdf")
    graph, _ = display
    graph.echo("/tf")  # robot_state_publisher is publishing
    folder = tmp_path / "frames"
    folder.mkdir()
    run = graph.tool(*ROBOMODEL, "run", "tf", "view_frames", cwd=folder)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert lines[:2] == ["Listening to /tf for 5.0 seconds", "Done Listening"]
    assert lines[-1] == "frames.pdf generated"
    text = (folder / "frames.gv").read_text()
    for parent, child in (("base_link", "link_1"), ("link_1", "link_2"), ("link_2", "gripper")):
        assert f'"{parent}" -> "{child}"' in text
    assert (folder / "frames.pdf").read_bytes().startswith(b"%PDF")


# --- "robot_description as parameter" -------------------------------------------------------


def _rosparam_steps(graph: SeedRos1, urdf_dir: Path, tool: list[str]) -> None:
    """The seed's rosparam lines, in its order, with ``tool`` as rosparam."""
    listed = graph.tool(*tool, "list")
    assert listed.returncode == 0, listed.stderr
    assert "/robot_description" in listed.stdout.split()
    got = graph.tool(*tool, "get", "/robot_description")
    assert '<robot name="planar_3dof">' in got.stdout, got.stderr
    assert graph.tool(*tool, "delete", "/robot_description").returncode == 0
    assert graph.tool(ROSPARAM, "get", "/robot_description").returncode != 0
    color = graph.tool(*tool, "set", "/color", "[150,55,210]")
    assert color.returncode == 0, color.stderr
    assert yaml.safe_load(graph.tool(ROSPARAM, "get", "/color").stdout) == [150, 55, 210]


def _rosparam_file_steps(graph: SeedRos1, urdf_dir: Path, tool: list[str]) -> None:
    run = graph.tool(*tool, "set", "/robot_description", "-t", "planar_3dof.urdf", cwd=urdf_dir)
    assert run.returncode == 0, run.stderr
    got = graph.tool(ROSPARAM, "get", "/robot_description").stdout
    assert yaml.safe_load(got) == PLANAR_3DOF_URDF


def _rosparam_namespace_steps(graph: SeedRos1, urdf_dir: Path, tool: list[str]) -> None:
    for name, value in (("p", "10"), ("i", "20"), ("d", "30")):
        run = graph.tool(*tool, "set", f"/gain/{name}", value)
        assert run.returncode == 0, run.stderr
    assert yaml.safe_load(graph.tool(ROSPARAM, "get", "/gain").stdout) == {
        "p": 10, "i": 20, "d": 30,
    }  # fmt: skip


def _rosparam_dump_load_steps(graph: SeedRos1, urdf_dir: Path, tool: list[str]) -> None:
    graph.tool(ROSPARAM, "set", "/gain/p", "10")
    dump = graph.tool(*tool, "dump", "parameters.yaml", cwd=urdf_dir)
    assert dump.returncode == 0, dump.stderr
    dumped = yaml.safe_load((urdf_dir / "parameters.yaml").read_text())
    assert dumped["gain"]["p"] == 10 and "planar_3dof" in dumped["robot_description"]
    assert graph.tool(ROSPARAM, "delete", "/gain").returncode == 0
    load = graph.tool(*tool, "load", "parameters.yaml", cwd=urdf_dir)
    assert load.returncode == 0, load.stderr
    assert yaml.safe_load(graph.tool(ROSPARAM, "get", "/gain/p").stdout) == 10


_PARAM_STEPS = [
    pytest.param(_rosparam_steps, "rosparam", id="list-get-delete-set-rosparam"),
    pytest.param(_rosparam_steps, "robomodel", id="list-get-delete-set-robomodel"),
    pytest.param(_rosparam_file_steps, "rosparam", id="set-t-file-rosparam"),
    pytest.param(_rosparam_file_steps, "robomodel", id="set-t-file-robomodel"),
    pytest.param(_rosparam_namespace_steps, "rosparam", id="set-namespace-rosparam"),
    pytest.param(_rosparam_namespace_steps, "robomodel", id="set-namespace-robomodel"),
    pytest.param(_rosparam_dump_load_steps, "rosparam", id="dump-load-rosparam"),
    pytest.param(_rosparam_dump_load_steps, "robomodel", id="dump-load-robomodel"),
]


@DISPLAY
@pytest.mark.parametrize(("steps", "tool"), _PARAM_STEPS)
def test_rosparam_steps_on_the_launch_s_master(
    display: tuple[SeedRos1, Path],
    steps: Callable[[SeedRos1, Path, list[str]], None],
    tool: str,
) -> None:
    """The seed's parameter-server lines against the master ``robomodel launch`` hosts, with
    Debian's rosparam and with ``robomodel param`` (checked by Debian's rosparam)."""
    graph, urdf_dir = display
    argv = [ROSPARAM] if tool == "rosparam" else [*ROBOMODEL, "param"]
    steps(graph, urdf_dir, argv)


@DISPLAY
def test_use_gui_set_by_hand(display: tuple[SeedRos1, Path]) -> None:
    """``rosparam set /use_gui true`` ("Set manually param if GUI is missing")."""
    graph, _ = display
    assert graph.tool(ROSPARAM, "set", "/use_gui", "true").returncode == 0
    assert graph.tool(ROSPARAM, "get", "/use_gui").stdout.strip() == "true"


# --- xacro ----------------------------------------------------------------------------------


def test_xacro_gives_the_same_robot_as_the_urdf(graph: SeedRos1) -> None:
    """``roslaunch xacro xacro.py model.xacro > model.urdf`` (the seed's typo for ``rosrun``) →
    ``robomodel xacro planar_3dof.xacro``; its output checks as the hand-written URDF does."""
    urdf = gripper_description(_src(graph), with_rviz=False) / "urdf"
    run = graph.tool(*ROBOMODEL, "xacro", "planar_3dof.xacro", cwd=urdf)
    assert run.returncode == 0, run.stderr
    (urdf / "model.urdf").write_text(run.stdout)
    ours = graph.tool(debian_check_urdf(), "model.urdf", cwd=urdf)
    hand = graph.tool(debian_check_urdf(), "planar_3dof.urdf", cwd=urdf)
    assert ours.returncode == 0 and ours.stdout == hand.stdout


def test_display_xacro_launch_loads_the_xacro_description(graph: SeedRos1, tmp_path: Path) -> None:
    """display_xacro.launch: robot_description from ``$(find xacro)/xacro.py``, use_gui set."""
    gripper_description(_src(graph), with_rviz=True)
    graph.launch(
        tmp_path / "xacro.log", "gripper_description", "display_xacro.launch", "--ros1-master",
        wait_for="nodes running",
    )  # fmt: skip
    description = yaml.safe_load(graph.tool(ROSPARAM, "get", "/robot_description").stdout)
    assert "planar_3dof" in description and 'velocity="0.5"' in description
    assert graph.tool(ROSPARAM, "get", "/use_gui").stdout.strip() == "true"
    assert graph.echo("/joint_states")["name"] == ["joint_1", "joint_2", "joint_3"]


# --- ros_control: the RRBot -----------------------------------------------------------------


def _rrbot_two_terminals(graph: SeedRos1, tmp_path: Path) -> None:
    """``roslaunch rrbot_gazebo rrbot_world.launch``, then ``roslaunch rrbot_control
    rrbot_control.launch`` in a second terminal."""
    rrbot_packages(_src(graph))
    graph.launch(
        tmp_path / "world.log", "rrbot_gazebo", "rrbot_world.launch", "--ros1-master",
        wait_for="Successfully spawned entity",
    )  # fmt: skip
    graph.launch(
        tmp_path / "control.log", "rrbot_control", "rrbot_control.launch", "--ros1-master",
        wait_for="Started controllers: joint_state_controller",
    )  # fmt: skip


RRBOT = pytest.mark.xdist_group("seed_000_rrbot")
"""The tests that look at the shared RRBot and move its joints: one worker starts it once."""

RRBOT_TO_CHANGE = pytest.mark.xdist_group("seed_000_rrbot_to_change")
"""The tests that change the controllers of a second RRBot, then end it: one worker, in this
file's order, starts it once (apart from the first, so that each group stays short)."""


def _shared_rrbot(tmp_path_factory: pytest.TempPathFactory) -> Iterator[SeedRos1]:
    home = tmp_path_factory.mktemp("rrbot")
    workspace = home / "catkin_ws" / "src"
    workspace.mkdir(parents=True)
    shared = SeedRos1(home, packages=str(workspace))
    try:
        _rrbot_two_terminals(shared, home)
        yield shared
    finally:
        shared.close()


@pytest.fixture(scope="module")
def rrbot(tmp_path_factory: pytest.TempPathFactory) -> Iterator[SeedRos1]:
    """One two-terminal RRBot, the first launch hosting the master, for the tests that look at
    it and move its joints (each starting its own took most of this module's time)."""
    yield from _shared_rrbot(tmp_path_factory)


@pytest.fixture(scope="module")
def rrbot_to_change(tmp_path_factory: pytest.TempPathFactory) -> Iterator[SeedRos1]:
    """Another, for the controller manager's commands (which put the controllers back as they
    found them) and then the Ctrl-C test, last in this file, which ends it."""
    yield from _shared_rrbot(tmp_path_factory)


@RRBOT
def test_rrbot_commands_move_the_joints(rrbot: SeedRos1) -> None:
    """``rostopic pub -1 /rrbot/joint1_position_controller/command std_msgs/Float64 "data:
    1.5"`` (and joint2 to 1.0): the simulated joints go there. The seed's gains are a PD (its
    ``I`` is not ``i``), so gravity leaves joint1 short of, or beyond, 1.5 by a little."""
    _commands_move_the_joints(rrbot)


def test_rrbot_commands_move_the_joints_beside_a_roscore(graph: SeedRos1, tmp_path: Path) -> None:
    """The same with ``roscore`` started first: the launches join it."""
    start_master(graph, "roscore")
    _rrbot_two_terminals(graph, tmp_path)
    _commands_move_the_joints(graph)


def _commands_move_the_joints(graph: SeedRos1) -> None:
    assert (
        float(graph.tool(ROSPARAM, "get", "/rrbot/joint1_position_controller/pid/p").stdout) == 100
    )
    for joint, value in (("joint1", "1.5"), ("joint2", "1.0")):
        topic = f"/rrbot/{joint}_position_controller/command"
        pub = graph.tool(ROSTOPIC, "pub", "-1", topic, "std_msgs/Float64", f"data: {value}")
        assert pub.returncode == 0, pub.stderr
    for joint, target in (("joint1", 1.5), ("joint2", 1.0)):
        until(
            lambda j=joint, t=target: (
                abs(joint_position(graph.echo("/rrbot/joint_states"), j) - t) < 0.3
            ),
            f"{joint} near {target}",
        )
    topics = graph.tool(ROSTOPIC, "list").stdout.split()
    assert {
        "/rrbot/joint1_position_controller/command",
        "/rrbot/joint1_position_controller/state",  # what the seed plots: .../state/process_value
        "/rrbot/joint2_position_controller/command",
        "/rrbot/joint_states",
        "/tf",
        "/clock",
    } <= set(topics)
    nodes = graph.tool(ROSNODE, "list").stdout.split()
    assert "/robot_state_publisher" in nodes
    # Debian has no control_msgs: robomodel's echo reads the controller's state
    state = graph.tool(
        *ROBOMODEL, "topic", "echo", "/rrbot/joint1_position_controller/state", "--once"
    )
    assert state.returncode == 0, state.stderr
    assert yaml.safe_load(state.stdout.split("---")[0])["set_point"] == 1.5


def _list_controllers(graph: SeedRos1) -> dict[str, tuple[str, str]]:
    """``robomodel control list-controllers`` for the /rrbot manager: name -> (type, state).
    (Debian has no controller_manager_msgs, so its rosservice cannot call the service.)"""
    run = graph.tool(*ROBOMODEL, "control", "list-controllers", "-c", "/rrbot/controller_manager")
    assert run.returncode == 0, run.stderr
    rows = [line.split() for line in run.stdout.splitlines() if line.strip()]
    return {row[0]: (row[1], row[2]) for row in rows}


@RRBOT
def test_rrbot_controllers_are_loaded_and_running(rrbot: SeedRos1) -> None:
    """The spawner's three controllers, all running, the position controllers with the
    YAML's type; the service the seed's rqt and ``controller_manager`` use is offered."""
    graph = rrbot
    services = graph.tool(ROSSERVICE, "list").stdout.split()
    assert "/rrbot/controller_manager/list_controllers" in services
    controllers = _list_controllers(graph)
    assert set(controllers) == {
        "joint_state_controller", "joint1_position_controller", "joint2_position_controller",
    }  # fmt: skip
    assert controllers["joint1_position_controller"][0] == (
        "effort_controllers/JointPositionController"
    )
    assert {state for _, state in controllers.values()} == {"active"}


@RRBOT
def test_rrbot_list_controllers_shows_the_yaml_s_types(rrbot: SeedRos1) -> None:
    assert _list_controllers(rrbot)["joint_state_controller"][0] == (
        "joint_state_controller/JointStateController"
    )


@RRBOT
def test_service_call_without_a_type_on_ros1(rrbot: SeedRos1) -> None:
    """``rosservice call /rrbot/controller_manager/list_controllers`` → ``robomodel service call
    ...``: the type is looked up as rosservice does."""
    run = rrbot.tool(*ROBOMODEL, "service", "call", "/rrbot/controller_manager/list_controllers")
    assert run.returncode == 0, run.stderr
    assert "joint1_position_controller" in run.stdout


@RRBOT_TO_CHANGE
def test_controller_manager_commands(rrbot_to_change: SeedRos1) -> None:
    """``controller_manager <command> <controller_name>`` (the seed's ``roslaunch`` is rosrun's
    job: ``rosrun controller_manager controller_manager``) → ``robomodel run controller_manager
    controller_manager``, in /rrbot: the seed's load, unload, start, stop, spawn and kill, with
    ROS 1's printed words and states (a loaded controller is ``initialized`` until started),
    then list-types (ROS 1's type names) and reload-libraries --restore; last the stopped
    controller is started again: the controllers are left as they were found."""
    graph = rrbot_to_change
    j1, j2 = "joint1_position_controller", "joint2_position_controller"

    def cm(*argv: str) -> str:
        run = graph.tool(*ROBOMODEL, "run", "controller_manager", "controller_manager", *argv,
                         "__ns:=/rrbot")  # fmt: skip
        assert run.returncode == 0, run.stdout + run.stderr
        return run.stdout

    def states() -> dict[str, str]:  # Noetic quotes the names: 'name' - 'interfaces' ( state )
        rows = [line.split(" - ") for line in cm("list").splitlines()]
        return {name.strip("'"): rest.rsplit("( ", 1)[1].rstrip(" )") for name, rest in rows}

    assert states() == {"joint_state_controller": "running", j1: "running", j2: "running"}
    assert cm("stop", j1) == f"Stopped ['{j1}'] successfully\n"
    assert states()[j1] == "stopped"
    assert cm("start", j1) == f"Started ['{j1}'] successfully\n"
    assert states()[j1] == "running"
    assert cm("kill", j2).splitlines() == [
        f"Stopped ['{j2}'] successfully", f"Unloaded '{j2}' successfully",
    ]  # fmt: skip
    assert j2 not in states()
    assert cm("load", j2) == f"Loaded '{j2}'\n"
    assert states()[j2] == "initialized"
    assert cm("unload", j2) == f"Unloaded '{j2}' successfully\n"
    assert j2 not in states()
    assert cm("spawn", j2).splitlines() == [f"Loaded '{j2}'", f"Started ['{j2}'] successfully"]
    assert states()[j2] == "running"
    types = cm("list-types").split()
    assert {"effort_controllers/JointPositionController",
            "joint_state_controller/JointStateController"} <= set(types)  # fmt: skip
    assert "joint_state_broadcaster/JointStateBroadcaster" not in types  # ROS 2's name
    assert cm("stop", j1) == f"Stopped ['{j1}'] successfully\n"
    assert cm("reload-libraries", "--restore").splitlines() == [
        "Restore: True", "Successfully reloaded libraries", "Controllers restored to original state",
    ]  # fmt: skip
    # as ros_control's script restores: every controller loaded again, the running ones started
    assert states() == {"joint_state_controller": "running", j1: "initialized", j2: "running"}
    assert cm("start", j1) == f"Started ['{j1}'] successfully\n"
    assert states() == dict.fromkeys(("joint_state_controller", j1, j2), "running")


@RRBOT
def test_rrbot_graph_has_rosout(rrbot: SeedRos1) -> None:
    """What ``rostopic list`` shows on any ROS 1 graph: /rosout and /rosout_agg."""
    topics = rrbot.tool(ROSTOPIC, "list").stdout.split()
    assert {"/rosout", "/rosout_agg"} <= set(topics)


@RRBOT_TO_CHANGE
def test_ctrl_c_ends_the_launches(rrbot_to_change: SeedRos1) -> None:
    """Ctrl-C in each terminal ends its launch (the shared RRBot's: this test is the last of
    this file's that use it)."""
    procs = rrbot_to_change.procs
    assert len(procs) == 2 and all(proc.poll() is None for proc in procs)
    for proc in reversed(procs):
        proc.send_signal(signal.SIGINT)
        assert proc.wait(scaled(60)) is not None
