"""``Robot`` equality is that of the robot, not of the document's order."""

from __future__ import annotations

import dataclasses
import warnings
from pathlib import Path

from robomodel.description import Link, Robot, parse_urdf, read_urdf
from robomodel.description.urdf.writer import urdf_to_string


def test_equality_different_link_order() -> None:
    # yourdfpy's tests/test_urdf.py::test_equality_different_link_order, transcribed.
    robot_0 = Robot(name="test_robot", links=(Link(name="link_0"), Link(name="link_1")))
    robot_1 = Robot(name="test_robot", links=(Link(name="link_1"), Link(name="link_0")))
    assert robot_0 == robot_1
    assert hash(robot_0) == hash(robot_1)


URDF = """<robot name="r">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint>
  <gazebo reference="a"><mu1>0.1</mu1></gazebo>
  <gazebo reference="a"><mu1>0.2</mu1></gazebo>
</robot>"""


def test_order_of_links_joints_materials_does_not_matter() -> None:
    robot = parse_urdf(URDF)
    shuffled = dataclasses.replace(
        robot,
        links=robot.links[::-1],
        joints=robot.joints[::-1],
        materials=robot.materials[::-1],
    )
    assert shuffled == robot and hash(shuffled) == hash(robot)
    # The writer keeps the order it is given: documents differ, robots do not.
    assert urdf_to_string(shuffled) != urdf_to_string(robot)
    assert parse_urdf(urdf_to_string(shuffled)) == robot


def test_content_still_matters() -> None:
    robot = parse_urdf(URDF)
    assert dataclasses.replace(robot, links=robot.links[:-1]) != robot
    assert dataclasses.replace(robot, links=(*robot.links, robot.links[0])) != robot  # a bag
    assert dataclasses.replace(robot, name="other") != robot
    renamed = dataclasses.replace(robot.joints[0], name="j9")
    assert dataclasses.replace(robot, joints=(renamed, robot.joints[1])) != robot


def test_gazebo_blocks_keep_their_order() -> None:
    # A later <gazebo> block for the same reference overrides an earlier one: order is meaning.
    robot = parse_urdf(URDF)
    assert dataclasses.replace(robot, gazebo=robot.gazebo[::-1]) != robot


def test_diagnostic_of_a_childless_element_points_at_it(tmp_path: Path) -> None:
    # `exc.element or element` took a childless lxml element as false (and lxml
    # warned with a FutureWarning), so the warning pointed at the parent <transmission>.
    path = tmp_path / "t.urdf"
    path.write_text(
        '<robot name="r">\n  <link name="a"/>\n  <transmission name="t">\n'
        "    <type>transmission_interface/SimpleTransmission</type>\n    <joint/>\n"
        "  </transmission>\n</robot>\n"
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error", FutureWarning)
        result = read_urdf(str(path))
    (diagnostic,) = result.diagnostics
    assert "needs a name attribute" in diagnostic.message
    assert (diagnostic.location.line, diagnostic.location.column) == (5, 5)
