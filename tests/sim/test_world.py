"""SDF worlds: the common subset, errors with file:line, unsupported parts warned and skipped."""

from __future__ import annotations

import math

import pytest

from robomodel.sim import Simulation, WorldError, default_world, parse_world, read_world
from robomodel.sim.world import ShapeKind

from .conftest import WALL_WORLD

WORLD = """<?xml version="1.0"?>
<sdf version="1.6">
  <world name="yard">
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://sun</uri></include>
    <gravity>0 0 -9.8</gravity>
    <physics type="ode"><max_step_size>0.002</max_step_size><real_time_factor>2</real_time_factor></physics>
    <model name="post">
      <static>true</static>
      <pose>1 2 0.5 0 0 1.5707963</pose>
      <link name="l"><pose>0.5 0 0 0 0 0</pose>
        <collision name="c"><geometry><cylinder><radius>0.1</radius><length>1</length></cylinder></geometry></collision>
      </link>
    </model>
    <model name="crate">
      <pose>-1 0 1 0 0 0</pose>
      <link name="l"><inertial><mass>2</mass></inertial>
        <collision name="c"><geometry><box><size>0.4 0.4 0.4</size></box></geometry>
          <surface><friction><ode><mu>0.3</mu></ode></friction></surface></collision>
      </link>
    </model>
    <model name="tree"><include><uri>model://tree</uri></include></model>
    <actor name="walker"/>
  </world>
</sdf>"""


def test_common_subset_is_read() -> None:
    with pytest.warns(UserWarning) as caught:
        world = parse_world(WORLD, path="yard.world")
    assert world.name == "yard" and world.timestep_s == 0.002 and world.real_time_factor == 2
    assert world.gravity == (0.0, 0.0, -9.8) and world.ground_plane and world.sun
    post, crate = world.shapes
    assert post.kind is ShapeKind.CYLINDER and post.mass_kg == 0.0
    x, y, z, *_ = post.pose  # link pose 0.5 m along the model's rotated x (yaw 90 deg)
    assert (x, y, z) == pytest.approx((1.0, 2.5, 0.5), abs=1e-6)
    assert crate.mass_kg == 2.0 and crate.friction == 0.3
    messages = " ".join(str(w.message) for w in caught)
    assert "yard.world:22" in messages and "<actor>" in messages


def test_world_objects_are_simulated() -> None:
    with pytest.warns(UserWarning):
        sim = Simulation(parse_world(WORLD))
    sim.step(1000)  # 2 s at 2 ms
    assert sim.time_s == pytest.approx(2.0)
    crate = sim.data.body("crate_1")
    assert crate.xpos == pytest.approx([-1.0, 0.0, 0.2], abs=0.01)  # fell flat onto the ground
    assert sim.model.body("crate_1").ipos == pytest.approx([0.0, 0.0, 0.0])
    assert sim.model.opt.gravity[2] == -9.8


def test_default_world_and_the_example_wall() -> None:
    assert default_world().ground_plane and default_world().timestep_s == 0.001
    wall = read_world(WALL_WORLD)
    (shape,) = wall.shapes
    assert shape.kind is ShapeKind.BOX and shape.pose[0] - shape.size[0] / 2 == pytest.approx(2.2)


@pytest.mark.parametrize(
    ("text", "where", "words"),
    [
        ("<sdf>\n<world>\n<model>\n</world></sdf>", ":4", "does not parse"),
        ("<sdf>\n<model/>\n</sdf>", ":1", "no <world>"),
        (
            "<sdf><world>\n<physics><max_step_size>-1</max_step_size></physics></world></sdf>",
            ":2",
            "positive",
        ),
        ("<sdf><world>\n<model name='m'><pose>1 2</pose></model></world></sdf>", ":2", "6 numbers"),
    ],
)
def test_bad_worlds_are_clear_errors(text: str, where: str, words: str) -> None:
    with pytest.raises(WorldError) as info:
        parse_world(text, path="bad.world")
    assert str(info.value).startswith(f"bad.world{where}") and words in str(info.value)


def test_missing_world_file() -> None:
    with pytest.raises(WorldError, match="cannot read world file"):
        read_world("/nonexistent/x.world")
    assert math.isfinite(default_world().real_time_factor)


def test_world_in_the_viewer_and_on_tf() -> None:
    """Static shapes drawn in ``world``; a moving crate follows the TF frame the simulator
    publishes for it; a welded prefixed robot hangs off ``world`` through a static transform."""
    pytest.importorskip("viser")
    from robomodel.loading import load
    from robomodel.runtime import Context, ManualClock
    from robomodel.runtime.msg import TFMessage
    from robomodel.runtime.qos import latched
    from robomodel.sim import Placement
    from robomodel.sim.bus import SimBridge
    from robomodel.sim.scenery import scenery_of

    from .conftest import RRBOT

    with pytest.warns(UserWarning):
        world = parse_world(WORLD)
    post, crate = scenery_of(world)
    assert (post.frame, post.kind, post.size_m[:2]) == ("world", "cylinder", (0.1, 1.0))
    assert post.xyz_m == pytest.approx((1.0, 2.5, 0.5), abs=1e-6)
    assert (crate.frame, crate.kind, crate.xyz_m) == ("crate_1", "box", (0.0, 0.0, 0.0))

    sim = Simulation(world)
    sim.add_robot(load(str(RRBOT)), placement=Placement("left_", (0.0, 3.0, 0.0)))
    context = Context(clock=ManualClock())
    SimBridge(sim, context)
    node = context.create_node("listener")
    static: list[TFMessage] = []
    moving: dict[str, tuple[float, float, float]] = {}
    node.create_subscription(TFMessage, "/tf_static", static.append, latched())

    def on_tf(msg: TFMessage) -> None:
        for t in msg.transforms:
            v = t.transform.translation
            moving[t.child_frame_id] = (v.x, v.y, v.z)

    node.create_subscription(TFMessage, "/tf", on_tf, 100)
    sim.run(1.0)
    context.spin_once(0.0)
    assert moving["crate_1"][2] == pytest.approx(0.2, abs=0.01)  # fell from z 1 onto the ground
    welds = {t.child_frame_id: t for m in static for t in m.transforms}
    weld = welds["left_world"]  # rrbot's root link "world", prefixed
    assert weld.header.frame_id == "world"
    assert (weld.transform.translation.x, weld.transform.translation.y) == (0.0, 3.0)
