"""SDF worlds: parsing (models, includes, plugins, physics), their errors, and loading them into a Simulation."""
import pytest
from conftest import PACKAGE_ROOT
from sdf_helpers import link, model, sdf

from turtle_sim_ode.models.builder import build_model
from turtle_sim_ode.models.description import GazeboSurface, Pose
from turtle_sim_ode.models.sdf_world import Include, parse_sdf_world
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.physics.settings import PhysicsParams
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.world.simulation import Simulation

WORLDS = PACKAGE_ROOT / "worlds"


# --- worlds ------------------------------------------------------------------------------
def test_empty_world():
    world = parse_sdf_world((WORLDS / "empty.world").read_text())
    assert (world.ground_plane, world.sun, world.models) == (True, True, [])
    assert world.includes == [Include("model://ground_plane")]  # a model like any other, built in (includes.py)
    assert world.warnings == []
    physics = world.physics
    assert (physics.max_step_size, physics.solver, physics.iterations) == (0.001, "quick", 50)
    assert (physics.real_time_factor, physics.real_time_update_rate) == (1.0, 1000.0)
    params = physics.apply(PhysicsParams(time_step=0.002, solver="world", erp=0.5))
    assert (params.time_step, params.solver, params.solver_iterations) == (0.001, "quick", 50)
    assert params.gravity == (0.0, 0.0, -9.81)
    assert params.erp == 0.5  # not set by the world: the simulator's value stays


def test_room_world_parses():
    world = parse_sdf_world((WORLDS / "room.world").read_text())
    assert world.ground_plane and world.warnings == []
    models = {m.name: m for m in world.models}
    assert list(models) == ["walls", "obstacle_box", "obstacle_cylinder", "push_box"]
    walls = models["walls"].model
    assert walls.static and len(walls.links) == 4
    sizes = sorted(walls.links[name].collisions[0].geometry.size for name in walls.links)
    assert sizes == [(6.0, 0.1, 0.5)] * 2 + [(6.2, 0.1, 0.5)] * 2
    assert models["obstacle_box"].model.static and models["obstacle_cylinder"].model.static
    box = models["push_box"]
    assert not box.model.static
    assert box.model.links["link"].inertial.mass == 2.0
    assert box.model.surfaces["link"] == GazeboSurface(mu1=0.5, mu2=0.5, kp=1e6, kd=100.0)
    assert box.spawn_pose == (1.0, -1.5, 0.15, 0.0, 0.0, 0.0)


def test_room_world_walls_stop_the_pushed_box_and_static_models_have_no_bodies():
    world = parse_sdf_world((WORLDS / "room.world").read_text())
    physics = PhysicsWorld(world.physics.apply(PhysicsParams()))
    built = {m.name: build_model(physics, m.model, m.spawn_pose) for m in world.models}
    assert [name for name, b in built.items() if b.bodies] == ["push_box"]
    assert built["walls"].link_pose("wall_east")[0] == pytest.approx((3.05, 0.0, 0.25))
    box = built["push_box"]
    for _ in range(200):
        physics.step()
    assert box.link_pose("link")[0][2] == pytest.approx(0.15, abs=1e-3)
    box.links["link"].body.setLinearVel((0.0, -6.0, 0.0))  # would slide 3.7 m without the wall
    for _ in range(1500):
        physics.step()
    position, _ = box.link_pose("link")
    assert position[1] == pytest.approx(-3.0 + 0.15, abs=0.02)  # against the south wall
    assert position[2] == pytest.approx(0.15, abs=2e-3)
    assert built["walls"].link_twist("wall_south") == ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def test_static_model_teleports_and_removes_only_its_geoms():
    world = parse_sdf_world((WORLDS / "room.world").read_text())
    physics = PhysicsWorld()
    built = {m.name: build_model(physics, m.model, m.spawn_pose) for m in world.models}
    assert physics.static_space.getNumGeoms() == 6
    obstacle = built["obstacle_box"]
    obstacle.set_pose(-1.0, 2.0, 0.25)
    position, quaternion = obstacle.link_pose("link")
    assert position == pytest.approx((-1.0, 2.0, 0.25)) and quaternion == pytest.approx((0, 0, 0, 1))
    assert obstacle.geoms["link"][0].getPosition() == pytest.approx((-1.0, 2.0, 0.25))
    built["walls"].remove()
    assert physics.static_space.getNumGeoms() == 2
    physics.step()  # still consistent


def test_world_includes_plugins_and_ignored_parts():
    world = parse_sdf_world(
        sdf(
            """<world name="w">
      <light name="l" type="directional"/>
      <include><uri>model://turtlebot3_burger</uri><name>robot</name>
        <pose>1 2 0 0 0 1.5</pose><static>false</static></include>
      <include><uri>model://table</uri></include>
      <plugin name="state" filename="libgazebo_ros_state.so"><ros_ns>/g</ros_ns></plugin>
      <actor name="walker"/>
      <physics type="ode"><gravity>0 0 -1</gravity></physics>
      <model name="ground_plane"><static>true</static><link name="link"><collision name="c">
        <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
      </collision></link></model>
    </world>""",
            "1.4",
        )
    )
    assert world.includes == [
        Include("model://turtlebot3_burger", "robot", Pose((1.0, 2.0, 0.0), (0.0, 0.0, 1.5)), False),
        Include("model://table"),
    ]
    assert [include.index for include in world.includes] == [1, 2]  # after the <light>
    assert world.plugins[0].params == {"ros_ns": "/g"}
    assert world.physics.gravity == (0.0, 0.0, -1.0)  # SDF 1.4 puts it in <physics>
    assert world.ground_plane and not world.sun and [model.name for model in world.models] == ["ground_plane"]
    assert world.models[0].index == 6  # after the includes, plugin, actor and physics, as written
    assert world.warnings == ["<world> <actor> is not supported, ignored"]


def test_world_physics_default_block_and_range():
    world = parse_sdf_world(
        sdf(
            '<world name="w"><physics type="ode"><max_step_size>0.01'
            '</max_step_size></physics><physics type="bullet" default="1">'
            "<ode><constraints><erp>2</erp></constraints></ode></physics>"
            "</world>"
        )
    )
    assert world.physics.max_step_size is None  # the default block is the second one
    # A world without a ground plane has no ground (Gazebo's World::Load adds none): no warning either.
    assert len(world.warnings) == 1 and "only its ODE settings" in world.warnings[0]
    with pytest.raises(ModelError, match="erp"):
        world.physics.apply(PhysicsParams())


def test_world_gravity_beyond_the_bound_is_refused():
    world = parse_sdf_world(sdf('<world name="w"><gravity>0 0 -1e6</gravity></world>'))
    with pytest.raises(ModelError, match=r"gravity .*-1000000"):
        world.physics.apply(PhysicsParams())


def test_world_errors():
    with pytest.raises(ModelError, match="two models are named 'm'"):
        parse_sdf_world(sdf(f'<world name="w">{model("m", link("a"))}{model("m", link("a"))}' f"</world>"))
    for physics, message in (
        ("<max_step_size>0</max_step_size>", "must be > 0"),
        ("<ode><solver><iters>2.5</iters></solver></ode>", "positive integer"),
    ):
        with pytest.raises(ModelError, match=message):
            parse_sdf_world(sdf(f'<world name="w"><physics type="ode">{physics}</physics></world>'))
    with pytest.raises(ModelError, match="quick or world"):
        parse_sdf_world(
            sdf('<world name="w"><physics type="ode"><ode><solver><type>pgs</type>' "</solver></ode></physics></world>")
        )


def test_a_world_without_gravity_gets_sdfs_default():
    """Issue 14: SDF's -9.8 as Gazebo gives it, not the simulator's own -9.81; a given <gravity> wins."""
    assert parse_sdf_world(sdf('<world name="w"></world>')).physics.apply(PhysicsParams()).gravity == (0, 0, -9.8)
    given = parse_sdf_world(sdf('<world name="w"><gravity>0 0 -9.81</gravity></world>'))
    assert given.physics.apply(PhysicsParams()).gravity == (0.0, 0.0, -9.81)


def test_a_world_model_with_a_nested_model_spawns_as_one_model():
    nested = model("table", link("top", "0 0 0.5 0 0 0"), '<model name="leg">' + link("foot") + "</model>", static=True)
    sim = Simulation()
    sim.load_world(parse_sdf_world(sdf(f'<world name="w">{nested}</world>')))
    assert list(sim.models) == ["table"]
    assert set(sim.models["table"].robot.links) == {"top", "leg::foot"}
    sim.get_link_state("table::leg::foot")  # Gazebo's scoped name resolves
