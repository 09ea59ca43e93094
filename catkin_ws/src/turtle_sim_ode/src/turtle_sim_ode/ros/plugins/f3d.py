"""gazebo_ros_f3d's topic (world.plugins.f3d): geometry_msgs/WrenchStamped on ``topicName`` in the robot namespace,
the total force and torque on a link in the world frame, after every step while someone listens
(GazeboRosF3D::UpdateChild); stamped with ``frameName`` under the namespace's tf_prefix, as upstream (which reads the
frame but does not turn the wrench into it)."""
from __future__ import annotations

from typing import List

import rospy
from geometry_msgs.msg import WrenchStamped

from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, plugin_topic, publisher
from turtle_sim_ode.ros.plugin_topics import own_tf_prefix, resolve_frame
from turtle_sim_ode.ros.wire import heard, release
from turtle_sim_ode.world.plugins.f3d import F3dConfig, LinkForce


class F3dPublisher(Periodic):
    def __init__(self, physics: PhysicsWorld, reader: LinkForce, config: F3dConfig, namespace: str) -> None:
        super().__init__(0.0)  # every step
        self._physics = physics
        self._reader = reader
        self._pub = publisher(plugin_topic(namespace, config.topic), WrenchStamped, 1)
        self._message = WrenchStamped()
        self._message.header.frame_id = resolve_frame(own_tf_prefix(namespace), config.frame)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not heard(self._pub):
            return
        force, torque = self._reader.wrench(self._physics.time_step)
        message = self._message
        message.header.stamp = stamp
        wrench = message.wrench
        wrench.force.x, wrench.force.y, wrench.force.z = force
        wrench.torque.x, wrench.torque.y, wrench.torque.z = torque
        self._pub.publish(message)

    def close(self) -> None:
        self._reader.close()
        release(self._pub)


def interfaces(context: ModelContext, config: F3dConfig) -> List[Periodic]:
    model = context.model
    link = context.body_link(config.body, "f3d")
    if link is None:
        return []
    reader = LinkForce(context.sim.physics, model, link)
    try:
        return [F3dPublisher(context.sim.physics, reader, config, context.namespace)]
    except BaseException:
        reader.close()
        raise
