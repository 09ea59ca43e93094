"""gazebo_ros_joint_state_publisher's topic (world.plugins.joint_state_publisher)."""
from __future__ import annotations

from typing import List

import rospy
from sensor_msgs.msg import JointState

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, topic_prefix
from turtle_sim_ode.ros.plugin_topics import period
from turtle_sim_ode.ros.wire import JointStatePacker, release
from turtle_sim_ode.world.plugins import JointStatesConfig


class JointStatePublisher(Periodic):
    """libgazebo_ros_joint_state_publisher.so: positions and velocities of the named joints."""

    def __init__(self, model: BuiltModel, config: JointStatesConfig, namespace: str) -> None:
        super().__init__(period(config.update_rate))
        self._handles = [model.joint(name) for name in config.joints]
        self._packer = JointStatePacker(list(config.joints))
        self._pub = packed_publisher(topic_prefix(namespace) + "joint_states", JointState)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not self._pub.heard():
            return
        handles = self._handles
        positions = [handle.angle() for handle in handles]
        velocities = [handle.rate() for handle in handles]
        self._pub.publish(self._packer.pack, stamp.secs, stamp.nsecs, positions, velocities)

    def close(self) -> None:
        release(self._pub)


def interfaces(context: ModelContext, config: JointStatesConfig) -> List[Periodic]:
    return [JointStatePublisher(context.model, config, context.namespace)]
