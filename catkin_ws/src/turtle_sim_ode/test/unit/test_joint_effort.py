"""Efforts held to a joint's limits each step as Gazebo classic holds them (gazebo/physics/Joint.cc,
Joint::CheckAndTruncateForce, called from Joint::SetForce, which gazebo_ros's apply_joint_effort calls every step):
no effort in the direction in which the joint already turns faster than its velocity limit, then the effort clamped
to the effort limit."""
import pytest
from world_helpers import floating

from turtle_sim_ode.control.ode_joint import truncated_effort

PENDULUM = """<robot name="pendulum">
  <link name="base"><inertial><mass value="100"/><inertia ixx="100" iyy="100" izz="100" ixy="0" ixz="0" iyz="0"/>
  </inertial></link>
  <link name="bar"><inertial><origin xyz="0.5 0 0"/><mass value="1"/>
  <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="hinge" type="continuous"><parent link="base"/><child link="bar"/><axis xyz="0 0 1"/>
    <limit effort="{effort}" velocity="{velocity}"/></joint>
</robot>"""


@pytest.mark.parametrize(
    "effort, rate, velocity_limit, effort_limit, expected",
    [
        (5.0, 0.5, 1.0, 10.0, 5.0),  # under both limits
        (5.0, 1.5, 1.0, 10.0, 0.0),  # too fast forwards: no push forwards
        (-5.0, 1.5, 1.0, 10.0, -5.0),  # braking is allowed
        (-5.0, -1.5, 1.0, 10.0, 0.0),
        (5.0, -1.5, 1.0, 10.0, 5.0),
        (50.0, 0.0, 1.0, 10.0, 10.0),  # clamped to the effort limit
        (-50.0, 0.0, 1.0, 10.0, -10.0),
        (50.0, 99.0, 0.0, 0.0, 50.0),  # no limits
        (50.0, 99.0, -1.0, -1.0, 50.0),  # SDF's "none"
    ],
)
def test_truncated_as_gazebo_does(effort, rate, velocity_limit, effort_limit, expected) -> None:
    assert truncated_effort(effort, rate, velocity_limit, effort_limit) == expected


def spun_up(effort_limit: float, velocity_limit: float, seconds: float = 1.0) -> float:
    sim = floating(("p", PENDULUM.format(effort=effort_limit, velocity=velocity_limit), (0, 0, 1, 0, 0, 0)))
    sim.apply_joint_effort("hinge", 2.0)
    for _ in range(int(seconds / sim.physics.time_step)):
        sim.step()
    return sim.joint_properties("hinge")["rate"][0]


def test_a_urdf_velocity_limit_holds_a_driven_joint() -> None:
    # 2 N m on about 0.35 kg m^2 reaches 1 rad/s in 0.2 s; without a limit it turns at 5.7 rad/s after 1 s
    assert spun_up(10.0, 1.0) == pytest.approx(1.0, abs=0.01)
    assert spun_up(10.0, 0.0) > 5.0


def test_a_urdf_effort_limit_truncates_the_effort() -> None:
    assert spun_up(0.5, 100.0) == pytest.approx(spun_up(10.0, 100.0) / 4, rel=0.01)
