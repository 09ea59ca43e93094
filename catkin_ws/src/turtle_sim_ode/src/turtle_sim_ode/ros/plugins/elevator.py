"""gazebo_ros_elevator's topic (world.plugins.elevator): std_msgs/String on ``topic`` in the robot namespace, a floor
number (GazeboRosElevator::OnElevator: std::stoi of the data, so leading blanks and a sign are read and what follows
the digits is ignored) asks for a ride; the elevator's work is a Simulation step hook run before each physics step.
Text without a leading number is warned of (upstream's std::stoi throws in the callback)."""
from __future__ import annotations

import re
from typing import List, Optional

import rospy
from std_msgs.msg import String

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, plugin_topic, subscriber
from turtle_sim_ode.ros.throttle import logwarn_every
from turtle_sim_ode.ros.wire import release
from turtle_sim_ode.world.entities import SCOPE
from turtle_sim_ode.world.plugins.elevator import Elevator, ElevatorConfig

_LEADING_INTEGER = re.compile(r"\s*([+-]?\d+)")
# std::stoi's range: an int of 32 bits.
_INT_RANGE = (-(2**31), 2**31 - 1)


def floor_number(text: str) -> Optional[int]:
    """std::stoi's reading of ``text``: leading blanks, a sign, digits (what follows them ignored); None where
    std::stoi would throw (no digits, or beyond a 32-bit int)."""
    match = _LEADING_INTEGER.match(text)
    if match is None:
        return None
    floor = int(match.group(1))
    return floor if _INT_RANGE[0] <= floor <= _INT_RANGE[1] else None


class ElevatorInterface(Periodic):
    def __init__(self, context: ModelContext, elevator: Elevator, config: ElevatorConfig) -> None:
        super().__init__(0.0)
        self._name = context.name
        self._elevator = elevator
        self.topic = plugin_topic(context.namespace, config.topic)
        self._sub = subscriber(self.topic, String, self._on_floor, 1)
        self._sim = context.sim
        self._key = f"{context.name}{SCOPE}elevator{SCOPE}{id(elevator)}"
        context.sim.step_hooks[self._key] = elevator
        for warning in config.warnings:
            rospy.logwarn("model %s: %s", context.name, warning)
        rospy.loginfo(
            "model %s: elevator on joints [%s] (lift), [%s] (door), floors asked on [%s]",
            context.name,
            config.lift_joint,
            config.door_joint,
            self.topic,
        )

    def _on_floor(self, message: String) -> None:
        floor = floor_number(message.data)
        if floor is None:
            logwarn_every(
                5.0,
                self._name + "/elevator",
                "%s: elevator: not a floor number: [%s]" % (self._name, message.data[:80]),
            )
            return
        self._elevator.move_to_floor(floor)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        """Nothing to publish: the work is the step hook's."""

    def close(self) -> None:
        if self._sim.step_hooks.get(self._key) is self._elevator:
            del self._sim.step_hooks[self._key]
        release(self._sub)


def interfaces(context: ModelContext, config: ElevatorConfig) -> List[Periodic]:
    """The plugin's ROS side; a joint that is not prismatic is logged and the model goes on without the plugin."""
    try:
        elevator = Elevator(context.model, config)
    except (KeyError, ModelError) as error:
        rospy.logerr("model %s: elevator plugin disabled: %s", context.name, error)
        return []
    return [ElevatorInterface(context, elevator, config)]
