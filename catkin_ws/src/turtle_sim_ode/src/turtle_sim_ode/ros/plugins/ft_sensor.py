"""gazebo_ros_ft_sensor's topic (world.plugins.ft_sensor): geometry_msgs/WrenchStamped on ``topicName`` in the robot
namespace at ``updateRate`` (0: every step) while someone listens, the wrench the joint carries in its child link's
frame, stamped with the child link's name under the namespace's tf_prefix (GazeboRosFT::Load and UpdateChild)."""
from __future__ import annotations

from typing import List

import rospy
from geometry_msgs.msg import WrenchStamped

from turtle_sim_ode.ros.periodic import ModelContext, Periodic, plugin_topic, publisher
from turtle_sim_ode.ros.plugin_topics import own_tf_prefix, period, resolve_frame
from turtle_sim_ode.ros.wire import heard, release
from turtle_sim_ode.world.plugins.ft_sensor import FtSensorConfig, JointWrench, sensor_joint
from turtle_sim_ode.world.plugins.p3d import noisy


class FtSensorPublisher(Periodic):
    def __init__(self, reader: JointWrench, config: FtSensorConfig, namespace: str) -> None:
        super().__init__(period(config.update_rate))
        self._reader = reader
        self._noise = config.gaussian_noise
        self._pub = publisher(plugin_topic(namespace, config.topic), WrenchStamped, 1)
        self._message = WrenchStamped()
        self._message.header.frame_id = resolve_frame(own_tf_prefix(namespace), reader.child)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not heard(self._pub):
            return
        force, torque = self._reader.wrench()
        message = self._message
        message.header.stamp = stamp
        wrench = message.wrench
        wrench.force.x, wrench.force.y, wrench.force.z = noisy(force, self._noise)
        wrench.torque.x, wrench.torque.y, wrench.torque.z = noisy(torque, self._noise)
        self._pub.publish(message)

    def close(self) -> None:
        release(self._pub)


def interfaces(context: ModelContext, config: FtSensorConfig) -> List[Periodic]:
    handle = sensor_joint(context.model, config.joint)  # ModelError for no such joint: the spawn is refused
    if handle is None:
        rospy.logwarn(
            "model %s: ft_sensor jointName [%s] is a fixed (or floating) joint, merged as Gazebo lumps fixed"
            " joints: not published",
            context.name,
            config.joint,
        )
        return []
    rospy.loginfo("model %s: ft_sensor reports the wrench of [%s]", context.name, config.joint)
    return [FtSensorPublisher(JointWrench(context.model, handle), config, context.namespace)]
