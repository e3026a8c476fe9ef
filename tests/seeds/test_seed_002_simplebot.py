"""Seed 002, "Lab exercise Nr. 1": simplebot_description (simplebot.urdf.xacro,
view_urdf.launch, simplebot_gazebo.launch) and simplebot_control (simplebot_controllers.launch
and .yaml, a diff_drive_controller driven on /simplebot_controller/cmd_vel), as the student
types them.

The seed is a PDF's text: underscores became spaces, comments lost their ``-->``, a ``<`` or a
``type:`` went missing, ``<pre>`` fragments were left in. Every such fix is named in a comment
(and in :data:`TYPO_FIXES`, applied to the seed's text below as written).
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml

from tests.conftest import ROBOMODEL
from tests.seeds.conftest import (
    MASTERS,
    ROSNODE,
    ROSTOPIC,
    SeedRos1,
    grouped_by_master,
    joint_position,
    package_xml,
    start_master,
    until,
    write_tree,
)
from tests.timing import scaled

# Step 4's simplebot.urdf.xacro as the seed prints it (its listing starts inside a comment).
SEED_XACRO = """-->
  <link name="base link">
    <!-- Inertia is used to simulate the physics of the robot
in simulator -->
    <inertial>
      <mass value="1.0"/>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <!--
      This is the most tricly part. It can be calculated
using a mesh and
      programs such as MeshLab. If you get these values
totally wrong your robot
      might just explode of fly away in the simulator.
      -->
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001"</pre>
iyz="0" izz="0.001"/>
    </inertial>
    <collision>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <geometry>
        <box size="0.7 0.2 0.075"/>
      </geometry>
    </collision>
    <visual>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <geometry>
        <box size="0.7 0.2 0.075"/>
      </geometry>
      <material name="white"/>
    </visual>
  </link>
  <!--
  Macro defining robot wheel. This macro can be used to
initialize multiple
  wheels. Macros can have parameters that make it possible to
change the behaviour
  of the actual URDF xml that is going to be generated when
this macro is instantiated
  <xacro:macro name="wheel" params="side side ind">
    <!--
    Each new robot part should have its own link. These links
have the same
    fields as the base link link.
    <link name="${side} wheel">
      <inertial>
        <mass value="0.5"/>
        <origin xyz="0 0 0" rpy="0 0 0"/>
        <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001"</pre>
ivz="0" izz="0.001"/>
      </inertial>
      <collision>
        <origin xyz="0 0 0" rpy="${M PI/2} 0 0"/>
        <geometry>
          <cylinder radius="0.075" length="0.05"/>
        </geometry>
      </collision>
      <visual>

  <origin xyz="0 0 0" rpy="${M PI/2} 0 0"/>

        <geometry>
          <cylinder radius="0.075" length="0.05"/>
        </geometry>
        <material name="black"/>
      </visual>
    </link>
    <!--
    Joints are used to connect links together. There are
several type of joints
    that we can have. The most common are revolute and
continuous. You can read
    more about them in URDF documentation.
    <joint name="${side} wheel joint" type="continuous">
      <parent link="base link"/>
      <child link="${side} wheel"/>
      <xacro:if value="${side ind}">
        <origin xyz="0.35 0.125 0" rpy="0 0 0"/>
      </xacro:if>
      <xacro:if value="${not side ind}">
        <origin xyz="0.35 -0.125 0" rpy="0 0 0"/>
</xacro:if>
      <axis xyz="0 1 0"/>
    </joint>
    <!--
    Transmissions are used by ros control. They are necessary
so that we can
    simulate joints that are then controlled by ros control
controllers
    <transmission name="${side} wheel tran">
      Type of transmission. These can be more sophisticated.
Have a look at
      documentation to get more info on this.
      <type>transmission interface/SimpleTransmission</type>
      <!--
      This should be the same as the joint that you defined
above. Again joints
      can be controlled in several ways. For example, we can
have velocity,
      position or effort controlled joints. This depends on
the motor controller
      that is used in the robot.
      <joint name="${side} wheel joint">
<hardwareInterface>hardware interface/VelocityJointInterface
/hardwareInterface>
      </joint>
      <!--
      Actuator is the same as the actual motor that rotates
the joint. The gear
      ration can be specified in mechanicalReduction
parameter.
      -->
      <actuator name="${side} wheel motor">
        <mechanicalReduction>1</mechanicalReduction>
      </actuator>
    </transmission>
  </xacro:macro>
  <!--
  Here you actually declare the wheels. This is the
initialization of the macro
  that we declared above. We also give different parameters
for each wheel
  <xacro:wheel side="left" side ind="1"/>
<xacro:wheel side="right" side_ind="0"/>
</robot>
"""

# (seed text, fixed text): the seed's artefacts, each fixed where it occurs
TYPO_FIXES: tuple[tuple[str, str], ...] = (
    # the listing starts inside a comment: the file's head is cut off. It holds the
    # declaration, <robot> and the M_PI the wheel macro uses (ROS's xacro defines only pi)
    ('-->\n  <link name="base link">', '<?xml version="1.0"?>\n<robot name="simplebot" '
     'xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
     '  <xacro:property name="M_PI" value="3.1415926535897931"/>\n  <link name="base link">'),
    # "</pre>" fragments of the web page inside the <inertia> tags
    ('iyy="0.001"</pre>\n', 'iyy="0.001"\n'),
    ('ivz="0"', 'iyz="0"'),  # "ivz" is the OCR's "iyz"
    ("${M PI/2}", "${M_PI/2}"),  # underscores read as spaces, from here on
    ("base link", "base_link"),
    ("side ind", "side_ind"),
    ("${side} wheel joint", "${side}_wheel_joint"),
    ("${side} wheel tran", "${side}_wheel_tran"),
    ("${side} wheel motor", "${side}_wheel_motor"),
    ("${side} wheel", "${side}_wheel"),
    ("transmission interface/", "transmission_interface/"),
    ("hardware interface/", "hardware_interface/"),
    ("VelocityJointInterface\n/hardwareInterface>", "VelocityJointInterface</hardwareInterface>"),
    # comments whose "-->" the PDF dropped: closed where their prose ends
    ("this macro is instantiated\n", "this macro is instantiated -->\n"),
    ("fields as the base_link link.\n", "fields as the base_link link. -->\n"),
    ("more about them in URDF documentation.\n", "more about them in URDF documentation. -->\n"),
    ("ros control\ncontrollers\n", "ros control\ncontrollers -->\n"),
    ("      Type of transmission.", "      <!-- Type of transmission."),  # lost "<!--" too
    ("documentation to get more info on this.\n", "documentation to get more info on this. -->\n"),
    ("that is used in the robot.\n", "that is used in the robot. -->\n"),
    ("parameters\nfor each wheel\n", "parameters\nfor each wheel -->\n"),
)  # fmt: skip

# Step 7: "add ros_control plugin to robot description file", inside <robot>
GAZEBO_PLUGIN = """<gazebo>
  <plugin name="gazebo_ros_control"
filename="libgazebo_ros_control.so" />
  </gazebo>
"""


def simplebot_xacro() -> str:
    text = SEED_XACRO
    for seed, fixed in TYPO_FIXES:
        assert seed in text, seed
        text = text.replace(seed, fixed)
    return text.replace("</robot>", GAZEBO_PLUGIN + "</robot>")


# Step 5's view_urdf.launch. Fixed: underscores (robot_description, joint_state_publisher,
# robot_state_publisher, simplebot_description, view_urdf.rviz), "</pre>" fragments, the
# comments' lost "-->", and "$(find)</pre>\nxacro)" for "$(find xacro)".
VIEW_URDF_LAUNCH = """<launch>
  <!--
  We first convert our robot description from xacro to urdf.
This urdf is then
  loaded into ros parameter robot description. -->
  <param name="robot_description" command="$(find xacro)/xacro --inorder '$(find simplebot_description)/urdf/simplebot.urdf.xacro'" />
  <!--
  We now start three nodes. ... rviz is ros 3D tool used to visualize various robot sensor
data. -->
  <node name="joint_state_publisher"
pkg="joint_state_publisher" type="joint_state_publisher" />
  <node name="robot_state_publisher"
pkg="robot_state_publisher" type="robot_state_publisher" />
  <node name="rviz" pkg="rviz" type="rviz" args="-d $(find simplebot_description)/config/view_urdf.rviz" required="true"
/>
</launch>
"""

# Step 6's simplebot_gazebo.launch (the seed's "simplebot gazebo.lauch"). Fixed: underscores,
# "</pre>", the NOTE comment's lost "-->" (and its doubled quote), as above.
SIMPLEBOT_GAZEBO_LAUNCH = """<launch>
  <!-- Load the environment for simulation -->
  <!-- Here you can give a different world name to load
different environments -->
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
    <!--
    NOTE: Uncomment this to launch a different world
    <arg name="world_name" value="$(find simplebot_gazebo)/worlds/YOUR_WORLD.world"/> -->
    <arg name="paused" value="false"/>
  </include>
 <!-- The URDF of the robot -->
  <param name="robot_description"
           command="$(find xacro)/xacro --inorder
                    '$(find simplebot_description)/urdf/simplebot.urdf.xacro'" />
  <!-- Spawn your robot in Gazebo simulator -->
  <node pkg="gazebo_ros" type="spawn_model"
name="spawn_model" args="-urdf -x 0 -y 0 -z 0.075 -param
robot_description -model SimpleBot"/>
</launch>
"""

# Step 7's simplebot_controllers.launch. Fixed as above (underscores, "</pre>", "-->").
SIMPLEBOT_CONTROLLERS_LAUNCH = """<launch>
  <!-- Run the robot simulation file that we previously
created -->
  <include file="$(find simplebot_description)/launch/simplebot_gazebo.launch"/>
  <!-- Load controller configurations from YAML file to
parameter server -->
  <rosparam file="$(find simplebot_control)/config/simplebot_controllers.yaml"
command="load"/>
  <!--
  Here we only need robot state publisher because
joint states are going to be
 published by our created controller
  -->
  <node name="robot_state_publisher"
pkg="robot_state_publisher" type="robot_state_publisher" />
  <!--
  This node loads all robot controllers. The names of the
controllers should
  match the names you give to each controller in the yaml
file.
  -->
  <node name="controller_spawner" pkg="controller_manager"
type="spawner" respawn="false" args="joint_state_controller
simplebot_controller"/>
</launch>
"""

# Step 7's simplebot_controllers.yaml. Fixed: underscores in keys and names, comment lines the
# PDF wrapped (continued with "#"), "type" lost before diff_drive_controller/DiffDriveController
# and its spaces ("type                : ..."), "publish rate : 80" → "publish_rate: 80".
SIMPLEBOT_CONTROLLERS_YAML = """# We will load two controllers here.
#
# First controller (joint_state_controller) takes the joint states from
# Gazebo simulator and publishes them to /joint_states topic.
# Second controller (simplebot_controller) is a diff_drive_controller.
joint_state_controller:
  # this defines the actual type of the loaded controller.
  type: joint_state_controller/JointStateController
  # the following are all the parameters of your controller.
  publish_rate: 80
# our second robot controller
simplebot_controller:
  # its type is a diff drive controller
  type: diff_drive_controller/DiffDriveController
  # now we define the remaining parameters.
  left_wheel: 'left_wheel_joint'
  right_wheel: 'right_wheel_joint'
  pose_covariance_diagonal: [0.001, 0.001, 1000000.0,
1000000.0, 1000000.0, 1000.0]
  twist_covariance_diagonal: [0.001, 0.001, 1000000.0,
1000000.0, 1000000.0, 1000.0]
"""

# Step 5: what RViz writes with "Save Config" after setting the fixed frame to base_link and
# adding RobotModel and TF, saved as config/view_urdf.rviz
VIEW_URDF_RVIZ = """Panels:
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
    Fixed Frame: base_link
    Frame Rate: 30
  Name: root
"""


def simplebot_packages(src: Path, *, with_rviz: bool) -> None:
    """Steps 1-7: the two packages (``simplebot description`` is the seed's
    ``simplebot_description``)."""
    files = {
        "package.xml": package_xml("simplebot_description"),
        "urdf/simplebot.urdf.xacro": simplebot_xacro(),
        "launch/view_urdf.launch": VIEW_URDF_LAUNCH,
        "launch/simplebot_gazebo.launch": SIMPLEBOT_GAZEBO_LAUNCH,
    }
    if with_rviz:
        files["config/view_urdf.rviz"] = VIEW_URDF_RVIZ
    write_tree(src / "simplebot_description", files)
    write_tree(
        src / "simplebot_control",
        {
            "package.xml": package_xml("simplebot_control"),
            "launch/simplebot_controllers.launch": SIMPLEBOT_CONTROLLERS_LAUNCH,
            "config/simplebot_controllers.yaml": SIMPLEBOT_CONTROLLERS_YAML,
        },
    )


def test_the_fixed_xacro_expands_to_the_seed_s_robot(ros1_graph: SeedRos1) -> None:
    """``xacro simplebot.urdf.xacro`` → ``robomodel xacro``: base_link, two wheels on
    continuous joints 0.35 m ahead and 0.125 m aside, their velocity transmissions."""
    src = Path(ros1_graph.packages)
    simplebot_packages(src, with_rviz=False)
    urdf_dir = src / "simplebot_description" / "urdf"
    run = ros1_graph.tool(*ROBOMODEL, "xacro", "simplebot.urdf.xacro", cwd=urdf_dir)
    assert run.returncode == 0, run.stderr
    links = re.findall(r'<link name="([^"]+)"', run.stdout)
    assert links == ["base_link", "left_wheel", "right_wheel"]
    assert '<origin rpy="0 0 0" xyz="0.35 -0.125 0"/>' in run.stdout
    assert "hardware_interface/VelocityJointInterface" in run.stdout
    (urdf_dir / "simplebot.urdf").write_text(run.stdout)
    check = ros1_graph.tool(*ROBOMODEL, "check", "simplebot.urdf", cwd=urdf_dir)
    assert check.returncode == 0, check.stdout + check.stderr
    assert "root Link: base_link has 2 child(ren)" in check.stdout


def test_view_urdf_launch_runs_before_view_urdf_rviz_exists(
    ros1_graph: SeedRos1, tmp_path: Path
) -> None:
    """Step 5: "After rviz is loaded ... save this rviz config": the file does not exist yet."""
    simplebot_packages(Path(ros1_graph.packages), with_rviz=False)
    ros1_graph.launch(
        tmp_path / "view.log", "simplebot_description", "view_urdf.launch", "--ros1-master",
        wait_for="nodes running",
    )  # fmt: skip
    assert "left_wheel_joint" in ros1_graph.echo("/joint_states")["name"]


@pytest.mark.parametrize("master", MASTERS)
def test_view_urdf_launch_publishes_the_wheels(
    ros1_graph: SeedRos1, tmp_path: Path, master: str
) -> None:
    """Step 5 with view_urdf.rviz saved: the wheels' joint states and their transforms."""
    start_master(ros1_graph, master)
    simplebot_packages(Path(ros1_graph.packages), with_rviz=True)
    ros1_graph.launch(
        tmp_path / "view.log", "simplebot_description", "view_urdf.launch", "--ros1-master",
        wait_for="nodes running",
    )  # fmt: skip
    states = ros1_graph.echo("/joint_states")
    assert sorted(states["name"]) == ["left_wheel_joint", "right_wheel_joint"]
    tf = ros1_graph.tool(
        *ROBOMODEL, "tf", "base_link", "left_wheel", "--once", "--timeout", f"{scaled(60):.1f}"
    )
    assert tf.returncode == 0 and "[0.350, 0.125, 0.000]" in tf.stdout, tf.stdout + tf.stderr


def test_simplebot_gazebo_launch_spawns_the_robot(ros1_graph: SeedRos1, tmp_path: Path) -> None:
    """Step 6: ``roslaunch simplebot_description simplebot_gazebo.launch``."""
    simplebot_packages(Path(ros1_graph.packages), with_rviz=True)
    log = tmp_path / "gazebo.log"
    ros1_graph.launch(
        log, "simplebot_description", "simplebot_gazebo.launch", "--ros1-master",
        wait_for="Successfully spawned entity",
    )  # fmt: skip
    nodes = ros1_graph.tool(ROSNODE, "list").stdout.split()
    assert "/gazebo" in nodes
    world = ros1_graph.tool(
        *ROBOMODEL, "service", "call", "/gazebo/get_world_properties",
        "gazebo_msgs/srv/GetWorldProperties",
    )  # fmt: skip
    assert world.returncode == 0, world.stderr
    assert "model_names=['SimpleBot']" in world.stdout or "- SimpleBot" in world.stdout, (
        world.stdout
    )


def _controllers_launch(graph: SeedRos1, tmp_path: Path) -> Path:
    """Step 7: ``roslaunch simplebot_control simplebot_controllers.launch``."""
    simplebot_packages(Path(graph.packages), with_rviz=True)
    log = tmp_path / "controllers.log"
    graph.launch(
        log, "simplebot_control", "simplebot_controllers.launch", "--ros1-master",
        wait_for="Started controllers",
    )  # fmt: skip
    return log


@pytest.fixture(scope="module", params=grouped_by_master("seed_simplebot"))
def simplebot(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[tuple[SeedRos1, Path]]:
    """Step 7's controllers launch on a graph whose master it hosts, or a ``roscore`` started
    first (the parameter): the graph and the launch's log. One of each per module, for the
    tests that look at it and drive it (each starting its own took most of their time)."""
    home = tmp_path_factory.mktemp("simplebot")
    workspace = home / "catkin_ws" / "src"
    workspace.mkdir(parents=True)
    graph = SeedRos1(home, packages=str(workspace))
    try:
        start_master(graph, request.param)
        yield graph, _controllers_launch(graph, home)
    finally:
        graph.close()


def test_the_robot_drives_on_cmd_vel_and_odom_follows(simplebot: tuple[SeedRos1, Path]) -> None:
    """Steps 8-9: the odom frame appears; a Twist on /simplebot_controller/cmd_vel (what Robot
    Steering publishes, here Debian's ``rostopic pub -r 10``) drives the robot forward, the
    wheels turn and the odometry follows."""
    ros1_graph, log = simplebot
    assert "Started controllers: joint_state_controller, simplebot_controller" in log.read_text()
    steering = ros1_graph.start(
        [ROSTOPIC, "pub", "-r", "10", "/simplebot_controller/cmd_vel", "geometry_msgs/Twist",
         "linear: {x: 0.5}"]
    )  # fmt: skip

    def odom_x() -> float:
        run = ros1_graph.tool(*ROBOMODEL, "topic", "echo", "/simplebot_controller/odom", "--once")
        assert run.returncode == 0, run.stderr
        message = yaml.safe_load(run.stdout.split("---")[0])
        return float(message["pose"]["pose"]["position"]["x"])

    until(lambda: odom_x() > 0.2, "odometry x past 0.2 m")
    assert joint_position(ros1_graph.echo("/joint_states"), "left_wheel_joint") > 1.0
    tf = ros1_graph.tool(
        *ROBOMODEL, "tf", "odom", "base_link", "--once", "--timeout", f"{scaled(60):.1f}"
    )
    assert tf.returncode == 0 and "Translation" in tf.stdout, tf.stderr
    ros1_graph.stop(steering)  # the module's other tests look at a robot that stands


@pytest.mark.parametrize(
    "simplebot", grouped_by_master("seed_simplebot", only="robomodel-master"), indirect=True
)
def test_joint_states_at_the_yaml_s_publish_rate(simplebot: tuple[SeedRos1, Path]) -> None:
    """``publish_rate : 80``: /joint_states stamps 1/80 s apart on average (simulated time;
    each one falls on a control update, as in ros_control). The rate is counted by the
    headers' ``seq``, which the publisher numbers: a message dropped for a subscriber that reads
    slowly (rostopic echo on a busy machine; queue_size as in ROS) is still counted."""
    ros1_graph, _ = simplebot
    run = ros1_graph.tool(ROSTOPIC, "echo", "-n", "161", "/joint_states")
    headers = [m["header"] for m in yaml.safe_load_all(run.stdout) if m]
    assert len(headers) == 161, run.stderr
    first, last = headers[0], headers[-1]
    span_s = (last["stamp"]["secs"] - first["stamp"]["secs"]) + (
        last["stamp"]["nsecs"] - first["stamp"]["nsecs"]
    ) * 1e-9
    rate_hz = (last["seq"] - first["seq"]) / span_s
    assert rate_hz == pytest.approx(80, abs=1)


@pytest.mark.parametrize(
    "simplebot", grouped_by_master("seed_simplebot", only="robomodel-master"), indirect=True
)
def test_list_controllers_shows_the_yaml_s_types(simplebot: tuple[SeedRos1, Path]) -> None:
    ros1_graph, _ = simplebot
    run = ros1_graph.tool(*ROBOMODEL, "control", "list-controllers")
    assert run.returncode == 0, run.stderr
    types = {row.split()[0]: row.split()[1] for row in run.stdout.splitlines() if row.strip()}
    assert types == {
        "joint_state_controller": "joint_state_controller/JointStateController",
        "simplebot_controller": "diff_drive_controller/DiffDriveController",
    }
