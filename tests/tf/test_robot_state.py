"""robot_state_publisher's transforms: statics, dynamics, skipped floating joints, prefixes."""

from __future__ import annotations

from robomodel.description import read_urdf
from robomodel.kinematics import Kinematics
from robomodel.tf import buffer_from_model, joint_state_defaults, robot_transforms

TEXT = """<robot name="r"><link name="world"/><link name="base"/><link name="cart"/><link name="arm"/><link name="cam"/>
<joint name="free" type="floating"><parent link="world"/><child link="base"/></joint>
<joint name="slide" type="planar"><parent link="base"/><child link="cart"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/></joint>
<joint name="turn" type="revolute"><parent link="cart"/><child link="arm"/><axis xyz="0 0 1"/><limit lower="0.5" upper="1.5" effort="1" velocity="1"/></joint>
<joint name="fix" type="fixed"><parent link="arm"/><child link="cam"/><origin xyz="0.1 0 0"/></joint>
</robot>"""


def test_publisher_semantics() -> None:
    kin = Kinematics(read_urdf(TEXT).robot)
    assert joint_state_defaults(kin) == {"turn": 1.0}
    q = kin.q_from_dict(joint_state_defaults(kin))
    dynamic, static = robot_transforms(kin, q, frame_prefix="r/")
    assert [(t.frame_id, t.child_frame_id) for t in dynamic] == [("r/cart", "r/arm")]
    # planar is published as its fixed origin; floating is not published at all.
    assert [(t.frame_id, t.child_frame_id) for t in static] == [
        ("r/base", "r/cart"),
        ("r/arm", "r/cam"),
    ]
    buf = buffer_from_model(kin, q, frame_prefix="r/")
    assert not buf.can_transform("r/world", "r/base")
    assert buf.can_transform("r/base", "r/cam")
