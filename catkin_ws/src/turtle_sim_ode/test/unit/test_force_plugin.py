"""libgazebo_ros_force.so: GazeboRosForce::Load needs bodyName and topicName; UpdateChild adds the last wrench, in the
world frame, to the link at every step (gazebo_plugins/src/gazebo_ros_force.cpp)."""
from __future__ import annotations

import math

import pytest

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.plugins import read_plugins
from turtle_sim_ode.world.plugins.force import FORCE, LinkWrench
from turtle_sim_ode.world.simulation import Simulation

BOX_SDF = """<sdf version="1.6"><model name="box"><link name="link">
  <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
  <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link></model></sdf>"""


def test_body_and_topic_are_required() -> None:
    with pytest.raises(ModelError, match="needs <bodyName> and <topicName>"):
        read_plugins("m", [GazeboPlugin(FORCE, "force", {"bodyName": "link"})], {}, [])
    (config,) = read_plugins(
        "m", [GazeboPlugin(FORCE, "force", {"bodyName": "m::link", "topicName": "push"})], {}, []
    ).configs
    assert (config.body, config.topic) == ("link", "push")


def test_the_last_wrench_lifts_the_box_every_step() -> None:
    sim = Simulation()
    sim.spawn_sdf("box", BOX_SDF, (0, 0, 0.1, 0, 0, 0))
    wrench = LinkWrench(sim.models["box"], "link")
    assert wrench.set((0.0, 0.0, 19.81), (0.0, 0.0, 0.0))  # 10 m/s^2 net up for a 1 kg box
    assert not wrench.set((math.nan, 0.0, 0.0), (0.0, 0.0, 0.0)) and wrench.force == (0.0, 0.0, 19.81)
    for _ in range(500):
        wrench.apply()
        sim.step()
    (_, _, z), _ = sim.models["box"].link_pose("link")
    assert z - 0.1 == pytest.approx(0.5 * 10.0 * 0.5**2, rel=0.02)
