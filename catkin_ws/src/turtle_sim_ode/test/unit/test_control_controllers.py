"""The simulated controllers of ros_controllers on fake joints (control_helpers.InertiaJoint): commands,
published states, diff_drive_controller's kinematics, limits and timeout, joint_trajectory_controller's splines
and goals. Expected values come from the upstream sources named in each test."""
from __future__ import annotations

import math

import pytest
from control_helpers import ARM_URDF, BASE_URDF, Rig

from turtle_sim_ode.control.diff_drive import Odometry, SpeedLimiter
from turtle_sim_ode.control.spline import Segment
from turtle_sim_ode.control.trajectory import (
    GOAL_TOLERANCE_VIOLATED,
    INVALID_GOAL,
    INVALID_JOINTS,
    SUCCESSFUL,
    Point,
    TrajectoryGoal,
)

BASE = {
    "type": "diff_drive_controller/DiffDriveController",
    "left_wheel": ["front_left_wheel", "rear_left_wheel"],
    "right_wheel": ["front_right_wheel", "rear_right_wheel"],
}
TRAJECTORY = {
    "type": "effort_controllers/JointTrajectoryController",
    "joints": ["shoulder", "elbow"],
    "gains": {"shoulder": {"p": 400.0, "d": 40.0}, "elbow": {"p": 400.0, "d": 40.0}},
    "constraints": {"goal_time": 0.5, "shoulder": {"goal": 0.02}, "elbow": {"goal": 0.02}},
}


def command(rig: Rig, controller: str, topic: str, value) -> None:
    kind, callback = rig.manager.find(controller).controller.inputs[topic]
    callback(value)


def sent(rig: Rig, controller: str, topic: str) -> list:
    return [payload for name, _, payload in rig.manager.find(controller).controller.drain() if name == topic]


# --- single joints and groups -----------------------------------------------------------------------------
def test_effort_position_controller_reaches_the_command():
    """effort_controllers JointPositionController::update: a Pid on the position error drives the effort; the
    command is held within the joint's limits (enforceJointLimits), and state goes out every 10th update."""
    rig = Rig(ARM_URDF)
    rig.start(
        "c", {"type": "effort_controllers/JointPositionController", "joint": "shoulder", "pid": {"p": 100.0, "d": 20.0}}
    )
    command(rig, "c", "command", 1.0)
    rig.run(3.0)
    assert rig.joints["shoulder"].pos == pytest.approx(1.0, abs=1e-3)
    command(rig, "c", "command", 5.0)  # beyond the upper limit 2.0
    rig.run(3.0)
    assert rig.joints["shoulder"].pos == pytest.approx(2.0, abs=1e-3)
    states = sent(rig, "c", "state")
    assert len(states) == 600 and states[-1]["set_point"] == 2.0 and states[-1]["p"] == 100.0


def test_forward_group_refuses_a_command_of_the_wrong_size():
    """forward_joint_group_command_controller.h commandCB: the message upstream logs, and nothing changes."""
    rig = Rig(ARM_URDF)
    rig.start("g", {"type": "effort_controllers/JointGroupEffortController", "joints": ["shoulder", "elbow"]})
    command(rig, "g", "command", [1.0])
    controller = rig.manager.find("g").controller
    assert controller.errors == ["Dimension of command (1) does not match number of joints (2)! Not executing!"]
    command(rig, "g", "command", [3.0, -4.0])
    rig.run(0.002)
    assert (rig.joints["shoulder"].effort, rig.joints["elbow"].effort) == (3.0, -4.0)


def test_joint_state_controller_rate_and_required_rate():
    """joint_state_controller.cpp: publish_rate is required; the first message at the first update (starting
    sets last_publish_time_ 1.001 periods back), then one a period in sim time; joints in the interface's
    (name-sorted) order."""
    rig = Rig(ARM_URDF)
    assert not rig.manager.load("js", {"type": "joint_state_controller/JointStateController"})
    assert "Parameter 'publish_rate' not set" in rig.errors()
    rig.start("js", {"type": "joint_state_controller/JointStateController", "publish_rate": 50.0})
    rig.run(1.0)
    messages = sent(rig, "js", "@joint_states")
    assert len(messages) == 1 + 50 and messages[0]["name"] == ["elbow", "shoulder"]


# --- diff_drive_controller --------------------------------------------------------------------------------------
def test_diff_drive_separation_and_radius_from_the_urdf():
    """diff_drive_controller.cpp setOdomParamsFromUrdf: separation = distance of the wheel joints' origins
    (0.56 m across in the fixture), radius = the wheel link's cylinder (0.165 m)."""
    rig = Rig(BASE_URDF)
    rig.start("base", BASE)
    controller = rig.manager.find("base").controller
    assert controller.separation == pytest.approx(0.56) and controller.radius == pytest.approx(0.165)


def test_diff_drive_wheel_velocities_and_timeout():
    """DiffDriveController::update: left = (v - w * ws / 2) / r, right = (v + w * ws / 2) / r with the
    multipliers applied; a command older than cmd_vel_timeout is taken as zero."""
    rig = Rig(BASE_URDF)
    rig.start(
        "base",
        dict(BASE, wheel_separation=0.5, wheel_radius=0.1, wheel_separation_multiplier=2.0, cmd_vel_timeout=0.25),
    )
    command(rig, "base", "cmd_vel", (0.5, 1.0))
    rig.run(0.01)
    wheels = rig.hw.joints
    assert wheels["front_left_wheel"].command == pytest.approx((0.5 - 1.0 * 1.0 / 2) / 0.1)
    assert wheels["rear_right_wheel"].command == pytest.approx((0.5 + 1.0 * 1.0 / 2) / 0.1)
    rig.run(0.3)
    assert wheels["front_right_wheel"].command == 0.0


def test_diff_drive_odometry_follows_the_wheels():
    rig = Rig(BASE_URDF, inertia=0.01)
    rig.start("base", dict(BASE, publish_rate=20.0))
    command(rig, "base", "cmd_vel", (0.4, 0.0))
    for _ in range(5):
        rig.run(0.1)
        command(rig, "base", "cmd_vel", (0.4, 0.0))
    odom = sent(rig, "base", "odom")
    assert len(odom) == 10 and odom[-1]["x"] == pytest.approx(0.2, abs=0.01)
    assert odom[-1]["linear"] == pytest.approx(0.4, abs=0.01)
    assert sent(rig, "base", "/tf") == []  # drained with odom above: both go out together
    assert odom[-1]["frame_id"] == "odom" and odom[-1]["child_frame_id"] == "base_link"


def test_speed_limiter_as_upstream():
    """speed_limiter.cpp SpeedLimiter::limit: jerk, then acceleration (dv within [min_acc, max_acc] * dt), then
    velocity; min_* default to -max_*."""
    limiter = SpeedLimiter(
        has_velocity_limits=True,
        max_velocity=1.0,
        min_velocity=-1.0,
        has_acceleration_limits=True,
        max_acceleration=2.0,
        min_acceleration=-2.0,
    )
    assert limiter.limit(5.0, 0.0, 0.0, 0.1) == pytest.approx(0.2)
    assert limiter.limit(5.0, 0.95, 0.9, 0.1) == pytest.approx(1.0)


def test_odometry_exact_integration():
    """odometry.cpp Odometry::integrateExact: a quarter circle of radius 1 ends at (1, 1)."""
    odometry = Odometry(10)
    odometry.integrate(math.pi / 2, math.pi / 2)
    assert (odometry.x, odometry.y, odometry.heading) == pytest.approx((1.0, 1.0, math.pi / 2))


@pytest.mark.parametrize(
    "change, message",
    [
        ({"left_wheel": "front_left_wheel"}, "#left wheels (1) != #right wheels (2)."),
        ({"left_wheel": []}, "empty list"),
        ({"right_wheel": 3}, "not a list of strings"),
        ({"left_wheel": ["front_left_wheel", "nowhere"]}, "Could not find resource 'nowhere'"),
        ({"pose_covariance_diagonal": [1.0]}, "pose_covariance_diagonal"),
    ],
)
def test_diff_drive_bad_parameters(change, message):
    rig = Rig(BASE_URDF)
    assert not rig.manager.load("base", dict(BASE, **change))
    assert any(message in e for e in rig.errors()), rig.errors()


# --- joint_trajectory_controller --------------------------------------------------------------------------------
def test_cubic_and_quintic_segments_meet_their_end_states():
    """quintic_spline_segment.h: cubic with velocities, quintic with accelerations; outside the span, the end
    position with zero velocity and acceleration (sampleWithTimeBounds)."""
    cubic = Segment.between(1.0, (0.0, 1.0, None), 3.0, (2.0, -1.0, None))
    assert cubic.sample(1.0)[:2] == pytest.approx((0.0, 1.0))
    assert cubic.sample(3.0)[:2] == pytest.approx((2.0, -1.0))
    quintic = Segment.between(0.0, (0.0, 0.0, 1.0), 2.0, (1.0, 0.5, -0.5))
    assert quintic.sample(0.0) == pytest.approx((0.0, 0.0, 1.0))
    assert quintic.sample(2.0) == pytest.approx((1.0, 0.5, -0.5))
    assert quintic.sample(5.0) == pytest.approx((1.0, 0.0, 0.0))
    linear = Segment.between(0.0, (0.0, None, None), 2.0, (1.0, None, None))
    assert linear.sample(1.0) == pytest.approx((0.5, 0.5, 0.0))


def goal(positions, seconds=1.0, names=("shoulder", "elbow"), goal_id="g1"):
    return TrajectoryGoal(list(names), [Point(list(positions), [], [], seconds)], goal_id=goal_id)


def test_trajectory_goal_succeeds():
    rig = Rig(ARM_URDF)
    rig.start("arm", TRAJECTORY)
    controller = rig.manager.find("arm").controller
    assert controller.submit(goal([0.5, -0.5])) == (SUCCESSFUL, "")
    rig.run(1.5)
    assert controller.results == [("g1", "succeeded", {"error_code": SUCCESSFUL, "error_string": ""})]
    # feedback while the goal ran, at action_monitor_rate (20 Hz default, joint_trajectory_controller_impl.h)
    assert {goal_id for goal_id, _ in controller.feedback} == {"g1"} and 15 <= len(controller.feedback) <= 30
    assert rig.joints["elbow"].pos == pytest.approx(-0.5, abs=0.02)


def test_trajectory_goal_out_of_reach_is_aborted():
    """joint_trajectory_controller_impl.h update: not within the goal tolerances goal_time after the end:
    GOAL_TOLERANCE_VIOLATED, with '<joint> goal error <value>'."""
    rig = Rig(ARM_URDF, inertia=50.0)  # 60 N m cannot swing 50 kg m^2 by 1.5 rad in 0.3 + 0.5 s
    rig.start("arm", dict(TRAJECTORY, gains={"shoulder": {"p": 1e4}, "elbow": {"p": 1e4}}))
    controller = rig.manager.find("arm").controller
    controller.submit(goal([1.5, 0.0], seconds=0.3))
    rig.run(1.0)
    goal_id, status, result = controller.results[0]
    assert (status, result["error_code"]) == ("aborted", GOAL_TOLERANCE_VIOLATED)
    assert result["error_string"].startswith("shoulder goal error ")


@pytest.mark.parametrize(
    "bad, code",
    [
        (goal([0.1], names=("shoulder",)), INVALID_JOINTS),
        (goal([0.1, 0.2], names=("shoulder", "wrist")), INVALID_JOINTS),
        (TrajectoryGoal(["shoulder", "elbow"], [Point([0, 0], [], [], 1.0), Point([1, 1], [], [], 1.0)]), INVALID_GOAL),
        (TrajectoryGoal(["shoulder", "elbow"], [Point([0.0], [], [], 1.0)]), INVALID_GOAL),
    ],
)
def test_trajectory_refusals(bad, code):
    """JointTrajectoryController::goalCB / initJointTrajectory: joints not the controller's (INVALID_JOINTS),
    times not strictly increasing or sizes wrong (INVALID_GOAL)."""
    rig = Rig(ARM_URDF)
    rig.start("arm", TRAJECTORY)
    assert rig.manager.find("arm").controller.submit(bad)[0] == code


def test_trajectory_needs_gains_for_effort_joints():
    """hardware_interface_adapter.h: PID gains from gains/<joint> (p required), else init fails."""
    rig = Rig(ARM_URDF)
    assert not rig.manager.load("arm", dict(TRAJECTORY, gains={"shoulder": {"p": 1.0}}))
    assert "Failed to initialize PID gains from ROS parameter server." in rig.errors()


# --- gripper_action_controller ---------------------------------------------------------------------------------
GRIPPER = {
    "type": "effort_controllers/GripperActionController",
    "joint": "elbow",
    "gains": {"elbow": {"p": 100.0, "d": 20.0}},
}


def test_gripper_reaches_the_goal_within_its_tolerance():
    """gripper_action_controller_impl.h checkForSuccess: |error| < goal_tolerance (0.01): succeeded, reached_goal."""
    rig = Rig(ARM_URDF)
    rig.start("gripper", GRIPPER)
    controller = rig.manager.find("gripper").controller
    assert controller.submit("g", 0.5, 50.0) == (True, "")
    rig.run(2.0)
    goal_id, status, result = controller.results[0]
    assert (goal_id, status, result["reached_goal"], result["stalled"]) == ("g", "succeeded", True, False)
    assert abs(result["position"] - 0.5) < 0.01


def test_gripper_without_effort_stalls():
    """checkForSuccess: no movement faster than stall_velocity_threshold for stall_timeout: aborted, stalled; the
    effort is clamped to the goal's max_effort (hardware_interface_adapter.h, here 0)."""
    rig = Rig(ARM_URDF)
    rig.start("gripper", dict(GRIPPER, stall_timeout=0.5))
    controller = rig.manager.find("gripper").controller
    controller.submit("g", 0.5, 0.0)
    rig.run(0.4)
    assert controller.results == []
    rig.run(0.2)
    assert controller.results[0][1] == "aborted" and controller.results[0][2]["stalled"]
