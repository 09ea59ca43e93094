"""Issue #31 bug 3: a skid-steer robot steers while it drives, under gazebo_ros_skid_steer_drive and under
ros_control's diff_drive_controller with DefaultRobotHWSim's velocity PID, and why the latter can fail.

Expected values from the sources:
- gazebo_ros_skid_steer_drive.cpp getWheelVelocities and diff_drive_controller.cpp update set the two sides at
  v -/+ w s / 2: without slip the robot would yaw at w. A skid steer scrubs its wheels sideways to turn, so it
  yaws slower, never faster: husky_control's and smb_control's control.yaml correct their odometry with
  wheel_separation_multiplier 1.875, i.e. the robots yaw at about 1 / 1.875 of w. Expected: w t / 1.875 (less a
  margin for the varying scrub) < yaw < w t.
- default_robot_hw_sim.cpp writeSim, VELOCITY_PID: effort = clamp(pid.computeCommand(command - velocity, period)),
  SetForce'd for the coming step with the velocity readSim read before it: an explicit loop. On a wheel whose
  friction is saturated (slipping, as a skid steer's are while it starts to turn) the wheel alone answers the
  effort, and the loop converges only while p dt / I < 2 (I the wheel's inertia about its axis). Beyond, the
  wheel chatters between the effort limits, the slip's friction averages out and the robot cannot steer: the
  SMB of issue #31 had p 100, izz 0.049, dt 1 ms (p dt / I = 2.04); the fixture here has izz 0.098."""
from __future__ import annotations

import math
from pathlib import Path

import pytest
from conftest import PACKAGE_ROOT, yaw_of
from control_helpers import SMB_DIFF_DRIVE as DIFF_DRIVE
from control_helpers import SMB_PID_GAINS as PID_GAINS
from control_helpers import SMB_WHEELS as WHEELS
from control_helpers import Rig, simulated
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.control.plugin import unstable_velocity_pids
from turtle_sim_ode.world.simulation import Simulation

MODELS = Path(PACKAGE_ROOT) / "test" / "models"
SKID_BOT = (MODELS / "skid_bot.urdf").read_text()
SMB_CONTROL = (MODELS / "smb_control.urdf").read_text()
SEPARATION_MULTIPLIER = 1.875  # smb_control / husky_control control.yaml
SCRUB_MARGIN = 0.8  # the scrub varies with the command: the lower bound is 80 % of 1 / 1.875
DRIVE_TIME = 3.0  # s of sim time
SETTLE_TIME = 0.5
commands = st.tuples(st.floats(0.2, 0.8), st.floats(0.3, 1.0), st.sampled_from([1.0, -1.0]))


def yaw_and_path(sim: Simulation, command, seconds: float):
    """Yaw change and distance of base_link while ``command(time)`` is applied for ``seconds``."""
    model = sim.models[next(iter(sim.models))]
    (x0, y0, _), q0 = model.link_pose("base_link")
    yaw, last, path = 0.0, yaw_of(q0), 0.0
    for _ in range(int(round(seconds / sim.physics.time_step))):
        command(sim.sim_time)
        sim.step()
        (x1, y1, _), q1 = model.link_pose("base_link")
        now = yaw_of(q1)
        yaw += (now - last + math.pi) % math.tau - math.pi
        path += math.hypot(x1 - x0, y1 - y0)
        last, x0, y0 = now, x1, y1
    return yaw, path


def assert_steers(yaw: float, path: float, v: float, w: float) -> None:
    turn = abs(w) * DRIVE_TIME
    assert math.copysign(1.0, yaw) == math.copysign(1.0, w)
    assert SCRUB_MARGIN * turn / SEPARATION_MULTIPLIER < abs(yaw) < turn, (yaw, turn)
    assert path > 0.7 * v * DRIVE_TIME, (path, v)  # it drives while it turns


@settings(max_examples=6, deadline=None)
@given(commands)
def test_skid_steer_drive_steers_while_driving(command) -> None:
    v, w, sign = command
    sim = Simulation()
    sim.spawn_urdf("smb", SKID_BOT, (0, 0, 0.2, 0, 0, 0))
    drive = sim.robots["smb"].drive
    yaw_and_path(sim, lambda now: drive.set_command(0.0, 0.0, now), SETTLE_TIME)
    yaw, path = yaw_and_path(sim, lambda now: drive.set_command(v, sign * w, now), DRIVE_TIME)
    assert_steers(yaw, path, v, sign * w)


@settings(max_examples=6, deadline=None)
@given(commands)
def test_diff_drive_controller_on_velocity_pid_wheels_steers_while_driving(command) -> None:
    v, w, sign = command
    sim, control = simulated(SMB_CONTROL, "smb", 0.2, {"smb_velocity_controller": DIFF_DRIVE}, PID_GAINS)
    assert {control.hw.control_method(wheel) for wheel in WHEELS} == {"VELOCITY_PID"}
    controller = control.manager.find("smb_velocity_controller").controller
    yaw_and_path(sim, lambda now: None, SETTLE_TIME)
    yaw, path = yaw_and_path(sim, lambda now: controller._on_cmd_vel((v, sign * w)), DRIVE_TIME)
    assert_steers(yaw, path, v, sign * w)


@pytest.mark.parametrize("inertia, converges", [(0.098, True), (0.06, True), (0.049, False), (0.03, False)])
def test_the_explicit_velocity_pid_converges_only_below_p_dt_over_inertia_2(inertia: float, converges: bool) -> None:
    """A free wheel (no ground: a slipping wheel's friction is a constant) under VELOCITY_PID p 100 at 1 ms."""
    rig = Rig(SMB_CONTROL, PID_GAINS, inertia=inertia)
    rig.joints["LF_WHEEL_JOINT"].vel = 2.0
    rig.hw.joints["LF_WHEEL_JOINT"].command = 3.0  # a command held, as diff_drive_controller's
    rig.run(0.2)
    error = abs(rig.joints["LF_WHEEL_JOINT"].vel - 3.0)
    if converges:
        assert error < 1e-6
    else:
        assert error > 0.5  # chattering between the effort limits (100 N m)


def test_a_velocity_pid_the_explicit_loop_cannot_hold_is_warned_about() -> None:
    """control.plugin.unstable_velocity_pids, as the ROS side logs it at spawn: p dt / I >= 2 on a wheel."""
    for inertia, warned in (("0.098", False), ("0.049", True)):
        urdf = SMB_CONTROL.replace('izz="0.098"', f'izz="{inertia}"')
        sim, control = simulated(urdf, "smb", 0.2, {}, PID_GAINS)
        inertias = {name: sim.models["smb"].joint(name).moved_inertia() for name in WHEELS}
        warnings = unstable_velocity_pids(control.hw, inertias, sim.physics.time_step)
        assert len(warnings) == (4 if warned else 0), warnings
        assert all(
            "pid_gains p 100 at 0.001 s steps" in warning and "(p dt / I = 2." in warning for warning in warnings
        )


SMB_COURSE = (MODELS / "smb_course_wheels.urdf").read_text()
# smb_control.yaml's smb_diff_drive limits: 2 m/s and 5 m/s^2, 2 rad/s and 5 rad/s^2
COURSE_LIMITS = {
    "has_velocity_limits": True,
    "max_velocity": 2.0,
    "has_acceleration_limits": True,
    "max_acceleration": 5.0,
}
COURSE_DIFF_DRIVE = dict(DIFF_DRIVE, linear={"x": COURSE_LIMITS}, angular={"z": COURSE_LIMITS})
COURSE_TIME = 4.0  # s, as the course drives it: 0.5 m/s for 4 s, "about 2 m"


@pytest.mark.parametrize("w", [0.0, 0.5])
def test_the_courses_smb_wheels_drive_and_steer_under_the_explicit_velocity_pid(w: float) -> None:
    """smb_description's wheels (test/models/smb_course_wheels.urdf: 5 kg, izz 0.049, front mu 0.5, LH 0, RH 0.2)
    under pid_gains p 100 at 1 ms: p dt / I = 2.04, so once a wheel slips (the 5 m/s^2 start asks 300 N of 177 N of
    friction; LH has none at all) its loop chatters between the effort limits, as default_robot_hw_sim.cpp writeSim's
    explicit loop on gazebo-classic's ODE (ODEJoint::SetForce, no implicit joint damping without
    <implicitSpringDamper>) must. Measured: 1.38 m straight, 1.25 m and 1.79 rad at 0.5 rad/s in 4 s (the
    commanded 2 m, 2 rad). It still steers while it drives; it loses about a third of its way to the chatter. The
    frictionless LH chatters in Gazebo too and shakes the others loose; with smb_common's later friction 0.7 on every
    wheel they roll and settle (test_smb_course_numbers.py: 1.96 m)."""
    sim, control = simulated(SMB_COURSE, "smb", 0.4, {"smb_velocity_controller": COURSE_DIFF_DRIVE}, PID_GAINS)
    controller = control.manager.find("smb_velocity_controller").controller
    yaw_and_path(sim, lambda now: None, 1.0)
    yaw, path = yaw_and_path(sim, lambda now: controller._on_cmd_vel((0.5, w)), COURSE_TIME)
    assert 0.5 * 0.5 * COURSE_TIME < path < 0.5 * COURSE_TIME, path
    if w == 0.0:
        assert abs(yaw) < 0.05, yaw
    else:
        assert SCRUB_MARGIN * w * COURSE_TIME / SEPARATION_MULTIPLIER < yaw < w * COURSE_TIME, yaw
