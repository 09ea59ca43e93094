"""Physics acceptance: the TurtleBot URDF driven by the diff drive at 1 ms steps.

Ground truth is base_footprint's pose in the physics state. Every scenario runs with
the quickstep solver (Gazebo's default, 50 iterations) and the exact 'world' solver.
"""
import math

import pytest
from conftest import TurtleSim, yaw_of

from turtle_sim_ode.analysis.path_fit import fit_circle


@pytest.fixture(params=["quick", "world"])
def solver(request):
    return request.param


def speed(sim):
    linear, _ = sim.model.link_twist("base_footprint")
    return math.hypot(linear[0], linear[1])


def test_straight_line(solver):
    sim = TurtleSim(solver)
    sim.settle()
    x0, y0, _ = sim.pose()
    sim.run(5.0, (0.3, 0.0))
    x, y, yaw = sim.pose()
    assert math.hypot(x - x0, y - y0) == pytest.approx(1.50, abs=0.03)
    assert abs(y - y0) < 0.01 and abs(yaw) < 0.01


def test_spin_in_place(solver):
    sim = TurtleSim(solver)
    sim.settle()
    x0, y0, _ = sim.pose()
    sim.run(2 * math.pi, (0.0, 1.0))
    x, y, yaw = sim.pose()
    assert math.hypot(x - x0, y - y0) < 0.01
    assert abs(yaw) < 0.05  # one whole turn


def test_circle_radius(solver):
    sim = TurtleSim(solver)
    sim.settle()
    sim.run(0.5, (0.5, 0.5))  # reach speed before fitting
    points = sim.run(2 * math.pi / 0.5, (0.5, 0.5), sample_period=0.05)
    _, radius = fit_circle(points)
    assert radius == pytest.approx(1.00, abs=0.02)


def test_encoder_odometry_tracks_ground_truth(solver):
    sim = TurtleSim(solver)
    sim.settle()
    start = sim.pose()
    path = [
        (0.5, 0.0, 6.0),
        (0.3, 0.5, 4.0),
        (0.4, -0.6, 5.0),
        (0.0, 1.0, 2.0),
        (0.5, 0.2, 6.0),
        (-0.2, 0.0, 2.0),
        (0.45, -0.3, 5.0),
    ]
    distance, previous = 0.0, start
    for linear, angular, seconds in path:
        for pose in sim.run(seconds, (linear, angular), sample_period=0.01):
            distance += math.hypot(pose[0] - previous[0], pose[1] - previous[1])
            previous = pose
    x, y, _ = sim.pose()
    error = math.hypot(x - start[0] - sim.odometry.x, y - start[1] - sim.odometry.y)
    assert distance > 10.0
    assert error <= 0.02 * distance


def test_no_creep_at_rest(solver):
    sim = TurtleSim(solver)
    sim.run(1.0)
    before = sim.model.link_pose("base_footprint")[0]
    sim.run(60.0)
    after = sim.model.link_pose("base_footprint")[0]
    assert math.dist(before, after) < 0.001


def test_drop_settles_at_resting_height(solver):
    resting = TurtleSim(solver)
    resting.run(1.0)
    sim = TurtleSim(solver, z=0.05)
    sim.run(1.0)
    position, quaternion = sim.model.link_pose("base_footprint")
    linear, angular = sim.model.link_twist("base_footprint")
    assert max(abs(v) for v in linear) < 1e-3 and max(abs(w) for w in angular) < 1e-2
    assert position[2] == pytest.approx(resting.model.link_pose("base_footprint")[0][2], abs=5e-4)
    # Within 1 mm of the 1 mm the TurtleBot's wheels and casters sink by their Gazebo <minDepth> (issue 14: per-link
    # minDepth now acts as in Gazebo; before, the world's 0.1 mm surface layer applied and the bound was 1 mm).
    assert abs(position[2] + 0.001) < 1e-3
    x, y, z, w = quaternion
    assert math.hypot(x, y) < 1e-3  # landed flat
    assert abs(yaw_of(quaternion)) < 1e-3


def test_command_timeout_stops_the_robot(solver):
    sim = TurtleSim(solver)
    sim.settle()
    sim.drive.set_command(0.3, 0.0, sim.physics.sim_time)
    x0, _, _ = sim.pose()
    sim.run(2.0)  # no further commands; cmd_timeout is the plugin's 0.6 s
    assert speed(sim) < 1e-3
    assert sim.pose()[0] - x0 == pytest.approx(0.3 * 0.6, abs=0.02)


def test_nan_command_is_ignored(solver):
    sim = TurtleSim(solver)
    sim.settle()
    sim.run(1.0, (0.3, 0.0))
    assert sim.drive.set_command(math.nan, 0.0, sim.physics.sim_time) is False
    sim.run(0.4, (math.nan, 0.5))
    assert speed(sim) == pytest.approx(0.3, abs=0.01)
    assert abs(sim.pose()[2]) < 0.01


def test_command_is_clamped(solver):
    sim = TurtleSim(solver, max_linear=0.5, max_angular=1.0)
    sim.settle()
    sim.run(1.0, (2.0, 0.0))
    assert speed(sim) == pytest.approx(0.5, abs=0.01)
    sim.run(1.0, (0.0, -5.0))
    assert sim.model.link_twist("base_footprint")[1][2] == pytest.approx(-1.0, abs=0.03)


def test_acceleration_limit_is_respected(solver):
    wheel_acceleration = 5.0  # rad/s^2, i.e. 0.175 m/s^2 at the rim
    sim = TurtleSim(solver, max_wheel_acceleration=wheel_acceleration)
    sim.settle()
    speeds, rates = [], []
    for _ in range(150):  # 1.5 s at 10 ms
        sim.run(0.01, (0.35, 0.0))
        speeds.append(speed(sim))
        rates.append(sim.left.rate())
    linear_limit = wheel_acceleration * sim.params.wheel_radius
    assert speeds[99] == pytest.approx(linear_limit * 1.0, abs=0.01)  # still ramping at 1 s
    for earlier, later in zip(speeds, speeds[1:]):
        assert later - earlier <= linear_limit * 0.01 * 1.1
    for earlier, later in zip(rates, rates[1:]):
        assert abs(later - earlier) <= wheel_acceleration * 0.01 * 1.1
