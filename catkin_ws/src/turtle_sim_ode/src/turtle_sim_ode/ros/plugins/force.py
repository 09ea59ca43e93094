"""gazebo_ros_force's topic (world.plugins.force): geometry_msgs/Wrench on ``topicName`` in the robot namespace; the
last one received is added to the link at every step (called after each step: ODE applies it in the next)."""
from __future__ import annotations

from typing import List

import rospy
from geometry_msgs.msg import Wrench

from turtle_sim_ode.ros.periodic import ModelContext, Periodic, plugin_topic, subscriber
from turtle_sim_ode.ros.throttle import logwarn_every
from turtle_sim_ode.ros.wire import release
from turtle_sim_ode.world.plugins.force import ForceConfig, LinkWrench


class ForceInterface(Periodic):
    def __init__(self, name: str, wrench: LinkWrench, config: ForceConfig, namespace: str) -> None:
        super().__init__(0.0)  # every step
        self._name = name
        self._wrench = wrench
        self._sub = subscriber(plugin_topic(namespace, config.topic), Wrench, self._on_wrench, 1)

    def _on_wrench(self, message: Wrench) -> None:
        force, torque = message.force, message.torque
        if not self._wrench.set((force.x, force.y, force.z), (torque.x, torque.y, torque.z)):
            logwarn_every(5.0, self._name + "/force", "%s: wrench ignored, not finite or too large" % self._name)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        self._wrench.apply()

    def close(self) -> None:
        release(self._sub)


def interfaces(context: ModelContext, config: ForceConfig) -> List[Periodic]:
    link = context.body_link(config.body, "force plugin", "no force")
    if link is None:
        return []
    return [ForceInterface(context.name, LinkWrench(context.model, link), config, context.namespace)]
