"""Fakes for the ros_control core's tests: joints that are point inertias, and a hardware built over them."""
from __future__ import annotations

from typing import Dict, List, Optional, Tuple

from conftest import PACKAGE_ROOT

from turtle_sim_ode.control.hardware import DefaultRobotHWSim
from turtle_sim_ode.control.manager import ControllerManager
from turtle_sim_ode.control.transmissions import read_transmissions
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.physics.settings import PhysicsParams

MODELS = PACKAGE_ROOT / "test" / "models"
ARM_URDF = (MODELS / "two_link_arm.urdf").read_text()
BASE_URDF = (MODELS / "four_wheel_base.urdf").read_text()
SMB_WHEELS = ("LF_WHEEL_JOINT", "RF_WHEEL_JOINT", "LH_WHEEL_JOINT", "RH_WHEEL_JOINT")
# the course's control.yaml (smb_control): gazebo_ros_control/pid_gains/<wheel>/p
SMB_PID_GAINS = {"gazebo_ros_control": {"pid_gains": {wheel: {"p": 100.0} for wheel in SMB_WHEELS}}}
# smb_common_v2's control.yaml: smb_velocity_controller on all four wheels, no limits (its linear/angular limits sit
# under gazebo_ros_control, where diff_drive_controller never reads them)
SMB_DIFF_DRIVE = {
    "type": "diff_drive_controller/DiffDriveController",
    "left_wheel": ["LF_WHEEL_JOINT", "LH_WHEEL_JOINT"],
    "right_wheel": ["RF_WHEEL_JOINT", "RH_WHEEL_JOINT"],
    "cmd_vel_timeout": 10.0,
    "enable_odom_tf": False,
}


class InertiaJoint:
    """A joint moving an inertia: an effort accelerates it; a velocity motor sets its speed if its force allows."""

    def __init__(self, inertia: float = 1.0, position: float = 0.0) -> None:
        self.inertia = inertia
        self.pos = position
        self.vel = 0.0
        self.effort = 0.0
        self.motor = None

    def position(self) -> float:
        return self.pos

    def velocity(self) -> float:
        return self.vel

    def apply_effort(self, effort: float) -> None:
        self.effort, self.motor = effort, None

    def drive(self, velocity: float, max_force: float) -> None:
        self.motor = (velocity, max_force)

    def step(self, dt: float) -> None:
        if self.motor is not None:
            target, force = self.motor
            change = max(-force * dt / self.inertia, min(force * dt / self.inertia, target - self.vel))
            self.vel += change
        else:
            self.vel += self.effort / self.inertia * dt
        self.pos += self.vel * dt


class Rig:
    """A parsed fixture robot, its joints as InertiaJoints, the hardware and a manager logging to a list."""

    def __init__(self, urdf: str, robot_params: dict = None, inertia: float = 1.0) -> None:
        self.robot = parse_urdf(urdf)
        transmissions, self.warnings = read_transmissions(self.robot)
        self.joints: Dict[str, InertiaJoint] = {t.name: InertiaJoint(inertia) for t in transmissions}
        self.hw = DefaultRobotHWSim(transmissions, self.joints, robot_params)
        self.log: List[Tuple[str, str]] = []
        self.manager = ControllerManager(self.hw, self.robot, lambda level, text: self.log.append((level, text)))
        self.time = 0.0

    def errors(self) -> List[str]:
        return [text for level, text in self.log if level == "error"]

    def run(self, seconds: float, dt: float = 0.001) -> None:
        for _ in range(int(round(seconds / dt))):
            self.time += dt
            self.hw.read()
            self.manager.update(self.time, dt)
            self.hw.write(dt)
            for joint in self.joints.values():
                joint.step(dt)

    def start(self, name: str, params: dict) -> None:
        assert self.manager.load(name, params), self.log
        assert self.manager.switch([name], [], 2), self.log


def simulated(
    urdf: str,
    name: str,
    z: float,
    controllers: dict,
    robot_params: Optional[dict] = None,
    physics: Optional[PhysicsParams] = None,
):
    """A Simulation (with ``physics``, default: PhysicsParams()) with the model spawned at height z and its ros_control
    stepped before every physics step, the controllers loaded and started, ``robot_params`` the robot namespace's
    parameters: (simulation, RosControl)."""
    from turtle_sim_ode.control.ode_joint import ode_sim_joints
    from turtle_sim_ode.control.plugin import RosControl, RosControlConfig
    from turtle_sim_ode.world.simulation import Simulation

    sim = Simulation(physics)
    sim.spawn_urdf(name, urdf, (0.0, 0.0, z, 0.0, 0.0, 0.0))
    model = sim.models[name]
    config = RosControlConfig.read({}, name, sim.physics.time_step)
    joints = ode_sim_joints(model)
    control = RosControl(config, model.robot, joints, robot_params or {}, lambda level, text: None)
    for controller, params in controllers.items():
        assert control.manager.load(controller, params)
    assert control.manager.switch(list(controllers), [], 2)
    sim.step_hooks[name] = control
    return sim, control
