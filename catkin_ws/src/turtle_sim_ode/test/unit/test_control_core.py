"""The ros_control core (turtle_sim_ode.control): transmissions and limits, control_toolbox's Pid, the
hardware simulation's control methods, and the controller manager's services. Expected values come from the
upstream sources named in each test."""
from __future__ import annotations

import math

import pytest
from control_helpers import ARM_URDF, BASE_URDF, InertiaJoint, Rig, simulated

from turtle_sim_ode.control.hardware import DefaultRobotHWSim, shortest_angular_distance
from turtle_sim_ode.control.manager import CONTROLLER_TYPES, ControllerManager
from turtle_sim_ode.control.params import ControllerError, Params
from turtle_sim_ode.control.pid import Pid, PidGains, read_gains
from turtle_sim_ode.control.plugin import RosControlConfig
from turtle_sim_ode.control.transmissions import EFFORT, VELOCITY, Limits, read_transmissions
from turtle_sim_ode.models.urdf import parse_urdf

EFFORT_POSITION = {"type": "effort_controllers/JointPositionController", "joint": "shoulder", "pid": {"p": 100.0}}


# --- transmissions ---------------------------------------------------------------------------------------
def test_transmissions_with_and_without_the_prefix():
    """default_robot_hw_sim.cpp, DefaultRobotHWSim::initSim: 'VelocityJointInterface' is taken as
    'hardware_interface/VelocityJointInterface' (with a deprecation warning in upstream)."""
    arm = read_transmissions(parse_urdf(ARM_URDF))[0]
    base = read_transmissions(parse_urdf(BASE_URDF))[0]
    assert [(j.name, j.interface) for j in arm] == [("shoulder", EFFORT), ("elbow", EFFORT)]
    assert {j.interface for j in base} == {VELOCITY} and len(base) == 4


def test_limits_from_the_urdf():
    """joint_limits_interface getJointLimits(urdf joint): position limits for revolute joints only, velocity and
    effort where > 0."""
    arm = read_transmissions(parse_urdf(ARM_URDF))[0]
    assert arm[0].limits == Limits(-2.0, 2.0, 3.0, 60.0)
    wheel = read_transmissions(parse_urdf(BASE_URDF))[0][0]
    assert wheel.limits == Limits(-math.inf, math.inf, 20.0, 80.0)


def transmission(body: str) -> str:
    return ARM_URDF.replace("</robot>", body + "</robot>")


@pytest.mark.parametrize(
    "body, warning",
    [
        ("<transmission name='t'><type>x</type></transmission>", "Transmission t has no associated joints."),
        ("<transmission name='t'><joint name='shoulder'/></transmission>", "does not specify any hardware"),
        (
            "<transmission name='t'><joint name='elbow'><hardwareInterface>EffortJointInterface</hardwareInterface>"
            "<hardwareInterface>PositionJointInterface</hardwareInterface></joint></transmission>",
            "Using the first entry",
        ),
    ],
)
def test_transmission_warnings_as_default_robot_hw_sim(body, warning):
    _, warnings = read_transmissions(parse_urdf(transmission(body)))
    assert any(warning in w for w in warnings), warnings


def test_a_joint_missing_from_the_model_or_an_unknown_interface_is_an_error():
    missing = "<transmission name='t'><joint name='wrist'><hardwareInterface>EffortJointInterface</hardwareInterface></joint></transmission>"
    with pytest.raises(ValueError, match='joint named "wrist" which is not in the gazebo model'):
        read_transmissions(parse_urdf(transmission(missing)))
    unknown = missing.replace("wrist", "elbow").replace("EffortJointInterface", "ImuSensorInterface")
    with pytest.raises(ValueError, match="No matching hardware interface found for 'ImuSensorInterface'"):
        read_transmissions(parse_urdf(transmission(unknown)))


# --- Pid -------------------------------------------------------------------------------------------------
def test_pid_gains_as_pid_init_reads_them():
    """control_toolbox pid.cpp Pid::init: p required, i and d default 0, i_clamp gives +-|i_clamp|."""
    gains = read_gains(Params({"p": 2.0, "i_clamp": -3.0}, "pid"))
    assert gains == PidGains(2.0, 0.0, 0.0, 3.0, -3.0, False)
    with pytest.raises(ControllerError, match="No p gain specified for pid.  Namespace: ns/pid"):
        read_gains(Params({"i": 1.0}, "ns/pid"))


def test_pid_compute_command():
    """pid.cpp Pid::computeCommand(error, dt): p*e + clamp(i * sum(e dt), i_min, i_max) + d * de/dt, the
    derivative 0 on the first call after reset; dt 0 or a non-finite error gives 0."""
    pid = Pid(PidGains(p=2.0, i=10.0, d=0.5, i_max=0.15, i_min=-0.15))
    assert pid.compute(1.0, 0.01) == pytest.approx(2.0 + 0.1 + 0.0)
    # i_error 0.02 -> i term 0.2 clamped to 0.15; de/dt = (0.5 - 1) / 0.01 = -50
    assert pid.compute(0.5, 0.01) == pytest.approx(1.0 + 0.15 - 25.0)
    assert pid.compute(math.nan, 0.01) == 0.0 and pid.compute(1.0, 0.0) == 0.0


def test_pid_antiwindup_clamps_the_integral():
    """pid.cpp: with antiwindup, i_error is kept within i_min/i and i_max/i."""
    pid = Pid(PidGains(p=0.0, i=2.0, i_max=1.0, i_min=-1.0, antiwindup=True))
    for _ in range(100):
        pid.compute(1.0, 0.1)
    assert pid.i_error == pytest.approx(0.5)


def test_shortest_angular_distance():
    """angles::shortest_angular_distance wraps into [-pi, pi]."""
    assert shortest_angular_distance(3.0, -3.0) == pytest.approx(2 * math.pi - 6.0)
    assert shortest_angular_distance(0.0, 1.0) == pytest.approx(1.0)


# --- the hardware simulation ------------------------------------------------------------------------------
def test_pid_gains_turn_velocity_joints_into_velocity_pid():
    """default_robot_hw_sim.cpp initSim: <ns>/gazebo_ros_control/pid_gains/<joint> makes VELOCITY
    VELOCITY_PID (and POSITION POSITION_PID); effort joints ignore it."""
    robot = parse_urdf(BASE_URDF)
    transmissions = read_transmissions(robot)[0]
    joints = {t.name: InertiaJoint() for t in transmissions}
    params = {"gazebo_ros_control": {"pid_gains": {"front_left_wheel": {"p": 5.0}}}}
    hw = DefaultRobotHWSim(transmissions, joints, params)
    assert hw.control_method("front_left_wheel") == "VELOCITY_PID"
    assert hw.control_method("rear_left_wheel") == "VELOCITY"
    hw.joints["front_left_wheel"].command = 2.0
    hw.joints["rear_left_wheel"].command = 50.0
    hw.write(0.001)
    assert joints["front_left_wheel"].effort == pytest.approx(10.0)  # p * (2 - 0)
    assert joints["rear_left_wheel"].motor == (20.0, 80.0)  # the velocity limit, the effort limit as force


def test_effort_commands_are_saturated():
    """joint_limits_interface EffortJointSaturationHandle: within +-effort limit."""
    rig = Rig(ARM_URDF)
    rig.hw.joints["shoulder"].command = 1000.0
    rig.hw.write(0.001)
    assert rig.joints["shoulder"].effort == 60.0


def test_plugin_parameters():
    """gazebo_ros_control_plugin.cpp Load: robotNamespace defaults to the model's name, controlPeriod to the
    physics step (an error is logged when it is faster)."""
    config = RosControlConfig.read({}, "arm", 0.001)
    assert (config.robot_namespace, config.control_period, config.robot_param) == ("arm", 0.001, "robot_description")
    faster = RosControlConfig.read({"controlPeriod": "0.0005"}, "arm", 0.001)
    assert "is faster than the gazebo simulation period" in faster.warnings[0]
    with pytest.raises(ValueError, match="robotSimType 'my_pkg/MyHW' is not simulated"):
        RosControlConfig.read({"robotSimType": "my_pkg/MyHW"}, "arm", 0.001)


# --- the controller manager ------------------------------------------------------------------------------
def test_load_refusals_name_the_reason():
    """controller_manager.cpp ControllerManager::loadController's messages."""
    rig = Rig(ARM_URDF)
    assert not rig.manager.load("c", {})
    assert "because the type was not specified" in rig.errors()[-1]
    assert not rig.manager.load("c", {"type": "my_controllers/Unknown"})
    assert "controller type 'my_controllers/Unknown' does not exist." in rig.errors()[-2]
    assert not rig.manager.load("c", {"type": "effort_controllers/JointPositionController", "joint": "shoulder"})
    assert rig.errors()[-1] == "Initializing controller 'c' failed"
    assert rig.manager.load("c", EFFORT_POSITION)
    assert not rig.manager.load("c", EFFORT_POSITION)
    assert "already loaded" in rig.errors()[-1]


def test_a_joint_of_another_interface_is_not_found():
    """hardware_interface ResourceManager::getHandle's message."""
    rig = Rig(ARM_URDF)
    params = {"type": "velocity_controllers/JointVelocityController", "joint": "shoulder"}
    assert not rig.manager.load("v", params)
    assert "Could not find resource 'shoulder' in 'hardware_interface::VelocityJointInterface'." in rig.errors()


def test_switch_strictness_and_conflicts():
    """controller_manager.cpp switchController: STRICT fails on an unknown name or a controller already running;
    BEST_EFFORT goes on; two running controllers may not claim one joint (RobotHW::checkForConflict)."""
    rig = Rig(ARM_URDF)
    assert rig.manager.load("a", EFFORT_POSITION)
    assert rig.manager.load("b", dict(EFFORT_POSITION, type="effort_controllers/JointEffortController"))
    assert not rig.manager.switch(["a", "nobody"], [], 2)
    assert "Could not start controller with name 'nobody' because no controller with this name exists" in rig.errors()
    assert rig.manager.switch(["a", "nobody"], [], 1)
    assert [entry[1] for entry in rig.manager.listing()] == ["running", "initialized"]
    assert not rig.manager.switch(["a"], [], 2) and rig.errors()[-1] == "Controller 'a' is already running"
    assert rig.manager.switch(["a"], [], 1)
    assert not rig.manager.switch(["b"], [], 1)
    assert rig.errors()[-1] == "Could not switch controllers, due to resource conflict"
    assert rig.manager.switch(["b"], ["a"], 2)
    assert [entry[1] for entry in rig.manager.listing()] == ["stopped", "running"]
    assert rig.manager.listing()[1][3] == [("hardware_interface::EffortJointInterface", ["shoulder"])]


def test_unload_only_a_stopped_controller():
    rig = Rig(ARM_URDF)
    rig.start("a", EFFORT_POSITION)
    assert not rig.manager.unload("a")
    assert "because it is still running" in rig.errors()[-1]
    assert rig.manager.switch([], ["a"], 2) and rig.manager.unload("a")
    assert not rig.manager.unload("a")
    assert "because no controller with this name exists" in rig.errors()[-1]


def test_reload_libraries_refused_while_loaded_unless_force_kill():
    rig = Rig(ARM_URDF)
    rig.start("a", EFFORT_POSITION)
    assert not rig.manager.reload_libraries(False)
    assert rig.manager.reload_libraries(True) and rig.manager.listing() == []


def test_controller_types_with_their_base_class():
    """list_controller_types answers every type with controller_interface::ControllerBase."""
    types = ControllerManager.types()
    assert ("diff_drive_controller/DiffDriveController", "controller_interface::ControllerBase") in types
    assert len(types) == len(CONTROLLER_TYPES)


def test_position_joints_without_gains_are_driven_to_the_command():
    """default_robot_hw_sim.cpp writeSim POSITION: the joint is put at the command (here: a velocity motor reaching
    it in one step, the effort limit as its force), saturated to the limits (PositionJointSaturationHandle: within
    [lower, upper] and velocity * period of the last command)."""
    rig = Rig(ARM_URDF.replace("EffortJointInterface", "PositionJointInterface"), inertia=0.01)
    assert rig.hw.control_method("shoulder") == "POSITION"
    rig.start("p", {"type": "position_controllers/JointPositionController", "joint": "shoulder"})
    kind, on_command = rig.manager.find("p").controller.inputs["command"]
    on_command(2.5)  # beyond the upper limit 2.0; the velocity limit is 3 rad/s
    rig.run(0.1)
    assert rig.joints["shoulder"].pos == pytest.approx(0.3, abs=0.01)
    rig.run(1.0)
    assert rig.joints["shoulder"].pos == pytest.approx(2.0, abs=1e-3)


def test_e_stop_zeroes_efforts_and_timing_restarts_after_a_reset():
    """gazebo_ros_control_plugin.cpp: with the e-stop active, efforts are 0; Reset() restarts the update timing."""
    from turtle_sim_ode.control.plugin import RosControl

    rig = Rig(ARM_URDF)
    config = RosControlConfig.read({"controlPeriod": "0.002"}, "arm", 0.001)
    control = RosControl(config, rig.robot, rig.joints, {}, lambda level, text: None)
    control.manager.load("e", {"type": "effort_controllers/JointEffortController", "joint": "shoulder"})
    control.manager.switch(["e"], [], 2)
    control.manager.find("e").controller.inputs["command"][1](5.0)
    control.step(0.0, 0.001)
    assert rig.joints["shoulder"].effort == 5.0
    control.e_stop = True
    control.step(0.001, 0.001)
    assert rig.joints["shoulder"].effort == 0.0
    control.e_stop = False
    updates = []
    update = control.manager.update
    control.manager.update = lambda time, period: updates.append(period) or update(time, period)
    for step in range(1, 5):  # 1 ms steps, a 2 ms control period: every other step
        control.step(0.001 + step * 0.001, 0.001)
    assert updates == pytest.approx([0.002, 0.002])
    control.reset()
    control.step(0.0, 0.001)
    assert len(updates) == 3


def test_the_arm_in_ode_reaches_commanded_angles_against_gravity():
    """The whole chain without ROS: ODE joints, DefaultRobotHWSim, effort JointPositionControllers (the YAML's
    gains), 3 s of sim time."""
    gains = {"p": 300.0, "i": 20.0, "d": 30.0, "i_clamp": 10.0}
    controllers = {
        f"{joint}_position": {"type": "effort_controllers/JointPositionController", "joint": joint, "pid": gains}
        for joint in ("shoulder", "elbow")
    }
    sim, control = simulated(ARM_URDF, "arm", 0.0, controllers)
    for joint, angle in (("shoulder", 0.6), ("elbow", -0.8)):
        control.manager.find(f"{joint}_position").controller.inputs["command"][1](angle)
    for _ in range(3000):
        sim.step()
    assert sim.models["arm"].joint("shoulder").angle() == pytest.approx(0.6, abs=0.02)
    assert sim.models["arm"].joint("elbow").angle() == pytest.approx(-0.8, abs=0.02)


def test_the_base_in_ode_drives_at_the_commanded_speed():
    """diff_drive_controller on ODE wheel motors: 0.4 m/s commanded, the base's speed after 2 s."""
    controllers = {
        "base": {
            "type": "diff_drive_controller/DiffDriveController",
            "left_wheel": ["front_left_wheel", "rear_left_wheel"],
            "right_wheel": ["front_right_wheel", "rear_right_wheel"],
            "cmd_vel_timeout": 10.0,
        }
    }
    sim, control = simulated(BASE_URDF, "base", 0.21, controllers)
    for _ in range(500):  # settle on the wheels
        sim.step()
    control.manager.find("base").controller.inputs["cmd_vel"][1]((0.4, 0.0))
    for _ in range(2000):
        sim.step()
    linear, _ = sim.models["base"].link_twist("base_link")
    assert math.hypot(linear[0], linear[1]) == pytest.approx(0.4, abs=0.02)
