"""gazebo_ros_control's GazeboRosControlPlugin, ROS-free: its SDF parameters, and the update that runs the
controller manager in sim time at the control period and writes the joints every physics step."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, List, Mapping, Optional

from turtle_sim_ode.control.hardware import DefaultRobotHWSim, SimJoint
from turtle_sim_ode.control.manager import ControllerManager
from turtle_sim_ode.control.transmissions import VELOCITY, read_transmissions
from turtle_sim_ode.models.description import RobotModel

ROBOT_SIM_TYPES = ("gazebo_ros_control/DefaultRobotHWSim",)
# Timestamps within this of the control period count as a full period (sim time is a sum of float steps).
TIME_EPSILON = 1e-9
# DefaultRobotHWSim::writeSim applies a VELOCITY_PID's effort explicitly, from the velocity read before the step: on a
# joint that moves only its own inertia I (a slipping or lifted wheel) the loop diverges once p * step / I reaches 2; a
# wheel rolling on the ground moves its share of the robot too (test/unit/test_smb_course_numbers.py).
EXPLICIT_LOOP_LIMIT = 2.0


@dataclass(frozen=True)
class RosControlConfig:
    """robotNamespace (default: the model's name; empty: the root), robotParam (robot_description), robotSimType, controlPeriod
    (default and minimum: the physics step), legacyModeNS (read, no effect in Noetic), eStopTopic."""

    robot_namespace: str
    robot_param: str
    robot_sim_type: str
    control_period: float
    e_stop_topic: str
    warnings: tuple

    @classmethod
    def read(cls, params: Mapping[str, str], model_name: str, physics_step: float) -> "RosControlConfig":
        warnings = []
        sim_type = params.get("robotSimType", ROBOT_SIM_TYPES[0]).strip()
        if sim_type not in ROBOT_SIM_TYPES:
            raise ValueError(f"robotSimType '{sim_type}' is not simulated (known: {', '.join(ROBOT_SIM_TYPES)})")
        period = physics_step
        if "controlPeriod" in params:
            try:
                period = float(params["controlPeriod"])
            except ValueError:
                raise ValueError(f"controlPeriod '{params['controlPeriod']}' is not a number") from None
            if not math.isfinite(period) or period <= 0:
                raise ValueError(f"controlPeriod must be > 0, got {params['controlPeriod']}")
            if period < physics_step:
                warnings.append(
                    f"Desired controller update period ({period} s) is faster than the gazebo simulation period "
                    f"({physics_step} s)."
                )
            elif period > physics_step:
                warnings.append(
                    f"Desired controller update period ({period} s) is slower than the gazebo simulation period "
                    f"({physics_step} s)."
                )
        # GazeboRosControlPlugin::Load: the element's value whenever it exists (empty: the root), else the model's name
        namespace = params.get("robotNamespace", model_name).strip()
        return cls(
            robot_namespace=namespace,
            robot_param=params.get("robotParam", "robot_description").strip(),
            robot_sim_type=sim_type,
            control_period=period,
            e_stop_topic=params.get("eStopTopic", "").strip(),
            warnings=tuple(warnings),
        )


def unstable_velocity_pids(hw: DefaultRobotHWSim, inertias: Mapping[str, float], time_step: float) -> List[str]:
    """A warning for each VELOCITY_PID joint whose p gain the explicit loop cannot hold on the joint's own inertia."""
    warnings = []
    for name, pid in hw.pids.items():
        ratio = pid.gains.p * time_step / inertias.get(name, math.inf)
        if hw.joints[name].interface == VELOCITY and ratio >= EXPLICIT_LOOP_LIMIT:
            warnings.append(
                f"joint '{name}': pid_gains p {pid.gains.p:g} at {time_step:g} s steps on its {inertias[name]:.3g} kg m^2 "
                f"(p dt / I = {ratio:.2f} >= {EXPLICIT_LOOP_LIMIT:g}): while it slips or is off the ground its "
                "velocity loop chatters between the effort limits (DefaultRobotHWSim's explicit PID, as in Gazebo; "
                "rolling, the wheel carries its share of the robot and settles)"
            )
    return warnings


class RosControl:
    """One robot's hardware simulation and controller manager."""

    def __init__(
        self,
        config: RosControlConfig,
        robot: RobotModel,
        sim_joints: Mapping[str, SimJoint],
        robot_params: Optional[Mapping[str, object]],
        log: Callable[[str, str], None],
    ) -> None:
        transmissions, warnings = read_transmissions(robot)
        for warning in list(config.warnings) + warnings:
            log("warn", warning)
        self.config = config
        self.hw = DefaultRobotHWSim(transmissions, sim_joints, robot_params)
        for warning in self.hw.warnings:
            log("warn", warning)
        self.manager = ControllerManager(self.hw, robot, log)
        self.last_update: Optional[float] = None
        self.e_stop = False

    def step(self, sim_time: float, physics_step: float) -> None:
        """Before each physics step: the controllers once a control period has passed, the joints every step."""
        if self.last_update is None:
            self.last_update = sim_time - self.config.control_period
        period = sim_time - self.last_update
        if period >= self.config.control_period - TIME_EPSILON:
            self.last_update = sim_time
            self.hw.read()
            self.manager.update(sim_time, period)
        if self.e_stop:
            for joint in self.hw.joints.values():
                joint.command = joint.position if joint.interface.endswith("PositionJointInterface") else 0.0
        self.hw.write(physics_step)

    def reset(self) -> None:
        """World reset: no negative periods afterwards."""
        self.last_update = None
