"""What the tests of Gazebo's world API on Simulation share: small models written for them (a box, an arm with a joint
of each kind) in a world without gravity, and ways to step it and to see that a refused request changed nothing."""
import math

import pytest

from turtle_sim_ode.physics.settings import PhysicsParams
from turtle_sim_ode.world.simulation import Simulation

NO_GRAVITY = PhysicsParams(gravity=(0.0, 0.0, 0.0))
YAW_90 = (0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5))  # (x, y, z, w)


def inertial(mass, xyz="0 0 0", moment=0.1):
    return (
        f'<inertial><mass value="{mass}"/><origin xyz="{xyz}"/><inertia ixx="{moment}" ixy="0" '
        f'ixz="0" iyy="{moment}" iyz="0" izz="{moment}"/></inertial>'
    )


BOX = f"""<robot name="box"><link name="box">{inertial(1.0)}
<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>"""

# A heavy base; "upper" turns about z 0.5 m up, with "tip" fixed 1 m along it (turned 90 degrees)
# and "slide" on a rail along it; "wheel" spins about y beside the base.
ARM = f"""<robot name="arm">
  <link name="base">{inertial(10.0, moment=10.0)}</link>
  <link name="upper">{inertial(1.0, "0.5 0 0")}</link>
  <link name="tip">{inertial(0.5)}</link>
  <link name="slide">{inertial(0.3)}</link>
  <link name="wheel">{inertial(0.2, moment=0.01)}</link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="tip_joint" type="fixed"><parent link="upper"/><child link="tip"/>
    <origin xyz="1 0 0" rpy="0 0 {math.pi / 2}"/></joint>
  <joint name="rail" type="prismatic"><parent link="upper"/><child link="slide"/>
    <origin xyz="0.5 0 0"/><axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="spin" type="continuous"><parent link="base"/><child link="wheel"/>
    <origin xyz="0 -0.5 0"/><axis xyz="0 1 0"/></joint>
</robot>"""


def run(sim, seconds):
    for _ in range(round(seconds / sim.physics.time_step)):
        sim.step()


def same_rotation(q1, q2):
    return abs(sum(a * b for a, b in zip(q1, q2))) == pytest.approx(1.0, abs=1e-9)


def floating(*models):
    """A zero-gravity world with (name, urdf, pose) models."""
    sim = Simulation(NO_GRAVITY)
    for name, urdf, pose in models:
        sim.spawn_urdf(name, urdf, pose)
    return sim


def snapshot(sim):
    """Everything a failed request must leave alone."""
    return (
        {name: [sim.get_link_state(f"{name}::{link}") for link in model.links] for name, model in sim.models.items()},
        sim.physics_properties(),
        list(sim.loads),
        sim.sim_time,
    )
