"""Section 7 of the benchmark (scripts/bench_sim.py), without ROS (issue #24): the cost of a 1 kHz ros_control
controller manager in real-time factor. The four-wheeled base of turtle_sim_ode's tests is stepped at 1 ms alone and
with gazebo_ros_control's update every step (DefaultRobotHWSim reading and writing four velocity joints, a
joint_state_controller and a diff_drive_controller driving it); the ROS side adds only the messages the controllers
publish (50 Hz each here). Beside them, the base with its wheel motors set once to the controllers' commands and no
controller manager: the base alone is not driven, so the share kept also counts ODE's cost of the four wheel motors
(a row each in the solver) and of the moving contacts, which any drive has; the share of that driven base is the
controller manager's own cost."""
from __future__ import annotations

import os
from typing import Any, Dict

from bench.physics import best_steps_per_second
from bench.plan import PACKAGE, Plan

BASE_URDF = os.path.join(PACKAGE, "test", "models", "four_wheel_base.urdf")
CONTROLLERS = {
    "joint_state_controller": {"type": "joint_state_controller/JointStateController", "publish_rate": 50.0},
    "base_controller": {
        "type": "diff_drive_controller/DiffDriveController",
        "left_wheel": ["front_left_wheel", "rear_left_wheel"],
        "right_wheel": ["front_right_wheel", "rear_right_wheel"],
        "cmd_vel_timeout": 1e9,
    },
}


def base_simulation(with_control: bool) -> Any:
    from turtle_sim_ode.control.ode_joint import OdeSimJoint
    from turtle_sim_ode.control.plugin import RosControl, RosControlConfig
    from turtle_sim_ode.world.simulation import Simulation

    sim = Simulation()
    with open(BASE_URDF) as urdf:
        sim.spawn_urdf("base", urdf.read(), (0.0, 0.0, 0.21, 0.0, 0.0, 0.0))
    if with_control:
        model = sim.models["base"]
        config = RosControlConfig.read({"controlPeriod": "0.001"}, "base", sim.physics.time_step)
        joints = {name: OdeSimJoint(model.joint(name)) for name in model.joints}
        control = RosControl(config, model.robot, joints, {}, lambda level, text: None)
        for name, params in CONTROLLERS.items():
            control.manager.load(name, params)
        control.manager.switch(list(CONTROLLERS), [], 2)
        control.manager.find("base_controller").controller.inputs["cmd_vel"][1]((0.5, 0.3))
        sim.step_hooks["base"] = control
    return sim


def driven_like(controlled: Any) -> Any:
    """The base alone, each wheel's motor set once as ``controlled``'s hardware last wrote it."""
    from turtle_sim_ode.control.ode_joint import OdeSimJoint

    sim = base_simulation(False)
    model = sim.models["base"]
    for name, joint in controlled.step_hooks["base"].hw.joints.items():
        OdeSimJoint(model.joint(name)).drive(joint.command, joint.motor_force)
    return sim


def ros_control_cost(plan: Plan) -> Dict[str, Any]:
    alone, controlled = base_simulation(False), base_simulation(True)
    if abs(alone.physics.time_step - 0.001) > 1e-12:
        raise ValueError("the default physics step is no longer 1 ms")
    controlled.step()  # the controllers' first update commands the wheels
    driven = driven_like(controlled)
    without, motors_only, with_control = best_steps_per_second(
        [alone.step, driven.step, controlled.step], plan.physics_steps, plan.physics_repeats
    )
    return {
        "control_period_s": 0.001,
        "without": {"steps_per_s": without, "rtf": without * 0.001},
        "driven": {"steps_per_s": motors_only, "rtf": motors_only * 0.001},
        "with": {"steps_per_s": with_control, "rtf": with_control * 0.001},
        "us_per_control_update": 1e6 / with_control - 1e6 / without,
        "us_per_manager_update": 1e6 / with_control - 1e6 / motors_only,
        "rtf_share_kept": with_control / without,
        "rtf_share_of_driven": with_control / motors_only,
    }


def table(value: Dict[str, Any]) -> list:
    return [
        "%-34s %9.0f steps/s  RTF %6.1f"
        % ("four-wheeled base alone, 1 ms", value["without"]["steps_per_s"], value["without"]["rtf"]),
        "%-34s %9.0f steps/s  RTF %6.1f  (its wheel motors on, no manager)"
        % ("the same base driven", value["driven"]["steps_per_s"], value["driven"]["rtf"]),
        "%-34s %9.0f steps/s  RTF %6.1f"
        % ("+ controller manager at 1 kHz", value["with"]["steps_per_s"], value["with"]["rtf"]),
        "%-34s %9.1f us  (RTF kept: %.0f %%)"
        % ("cost of one control update", value["us_per_control_update"], 100 * value["rtf_share_kept"]),
        "%-34s %9.1f us  (RTF kept: %.0f %% of the base driven)"
        % ("of which the manager's own", value["us_per_manager_update"], 100 * value["rtf_share_of_driven"]),
    ]
