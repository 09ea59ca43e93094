"""Models by name in one world: spawning, refusing bad names and models, deleting, and driving."""
import math

import pytest
from conftest import TURTLEBOT_URDF

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.values import WorldError

BOX_URDF = """<robot name="box"><link name="box"><inertial><mass value="1"/>
<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
<gazebo><plugin name="cam" filename="libgazebo_ros_camera.so"/></gazebo></robot>"""


def test_spawn_and_delete():
    sim = Simulation()
    assert sim.spawn_urdf("mobile_base", TURTLEBOT_URDF) == []
    assert "mobile_base" in sim.robots
    warnings = sim.spawn_urdf("box", BOX_URDF, (2, 0, 0.1, 0, 0, 0))
    assert warnings == ["1 plugin(s) not supported, ignored: libgazebo_ros_camera.so"]
    assert "box" not in sim.robots
    sim.delete("box")
    assert set(sim.models) == {"mobile_base"}
    with pytest.raises(WorldError, match="model 'box' does not exist"):
        sim.delete("box")


@pytest.mark.parametrize(
    "name, urdf, message",
    [
        ("", BOX_URDF, "model name is empty"),
        ("mobile_base", BOX_URDF, "a model named 'mobile_base' already exists"),
        ("broken", "<robot", "line 1"),
        (
            "wrong_joint",
            TURTLEBOT_URDF.replace("<left_wheel_joint_name>wheel_left_joint", "<left_wheel_joint_name>no_such_joint"),
            "no_such_joint",
        ),
    ],
)
def test_bad_spawns_leave_the_world_unchanged(name, urdf, message):
    sim = Simulation()
    sim.spawn_urdf("mobile_base", TURTLEBOT_URDF)
    bodies_before = len(sim.models["mobile_base"].bodies)
    with pytest.raises(ModelError) as error:
        sim.spawn_urdf(name, urdf)
    assert message in str(error.value)
    assert set(sim.models) == {"mobile_base"} and len(sim.models["mobile_base"].bodies) == bodies_before


def test_step_drives_every_robot():
    sim = Simulation()
    sim.spawn_urdf("a", TURTLEBOT_URDF, (0, 0, 0, 0, 0, 0))
    sim.spawn_urdf("b", TURTLEBOT_URDF, (0, 2, 0, 0, 0, math.pi / 2))
    for name in ("a", "b"):
        sim.robots[name].drive.set_command(0.2, 0.0, sim.sim_time)
    for _ in range(500):
        sim.step()
    for name in ("a", "b"):
        sim.robots[name].update_odometry(sim.sim_time)
    a, _ = sim.models["a"].link_pose("base_footprint")
    b, _ = sim.models["b"].link_pose("base_footprint")
    assert a[0] > 0.05 and abs(a[1]) < 0.01
    assert b[1] > 2.05 and abs(b[0]) < 0.01


def _run_scripted_world():
    """Two robots and a box they collide with, driven by a fixed command script; every link's pose at the end."""
    sim = Simulation()
    sim.spawn_urdf("a", TURTLEBOT_URDF, (0, 0, 0, 0, 0, 0))
    sim.spawn_urdf("b", TURTLEBOT_URDF, (1.2, 0, 0, 0, 0, math.pi))
    sim.spawn_urdf("box", BOX_URDF, (0.6, 0.05, 0.1, 0, 0, 0))
    for linear, angular, steps in [(0.3, 0.0, 1200), (0.2, 0.8, 500), (-0.2, -0.5, 500)]:
        for name in ("a", "b"):
            sim.robots[name].drive.set_command(linear, angular, sim.sim_time)
        for _ in range(steps):
            sim.step()
    return {name: [model.link_pose(link) for link in model.links] for name, model in sim.models.items()}


def test_same_script_gives_bitwise_identical_poses():
    """Lockstep's promise (/gazebo/step_simulation): same spawns and commands, same poses to the last bit."""
    first, second = _run_scripted_world(), _run_scripted_world()
    assert first == second
    assert first["box"][0][0] != (0.6, 0.05, 0.1)  # the robots did push the box
