"""gazebo_ros_tricycle_drive's topics (world.plugins.tricycle_drive), as GazeboRosTricycleDrive has them:
``commandTopic`` (geometry_msgs/Twist: linear.x the speed, angular.z the steering angle) in; at ``updateRate``,
whether anyone listens or not (UpdateChild, publishOdometry): ``odometryTopic`` (nav_msgs/Odometry) and tf
``odometryFrame`` -> ``robotBaseFrame``, plus, if asked, tf of each of the four joints (publishWheelTF) and
``joint_states`` (publishWheelJointState). Frames under the ``tf_prefix`` parameter (GazeboRos::resolveTF,
tf::getPrefixParam: none when it is not set)."""
from __future__ import annotations

import math
from typing import List, Optional, Tuple

import rospy
from sensor_msgs.msg import JointState

from turtle_sim_ode.models.transforms import compose, inverse
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, plugin_topic
from turtle_sim_ode.ros.plugin_topics import Vec3, resolve_frame
from turtle_sim_ode.ros.plugins.drive import GazeboDriveInterface, gazebo_drive_interfaces, yaw_frame_odometry
from turtle_sim_ode.ros.wire import JointStatePacker, PackedPublisher, Quat, TransformPacker, release
from turtle_sim_ode.world.plugins.tricycle_drive import TricycleConfig, TricycleRobot
from turtle_sim_ode.world.simulation import Simulation

# publishOdometry's pose covariance (x, y 1e-5; z, roll, pitch 1e12; yaw 1e-3); its twist covariance stays 0.
POSE_COVARIANCE = tuple({0: 1e-5, 7: 1e-5, 14: 1e12, 21: 1e12, 28: 1e12, 35: 1e-3}.get(i, 0.0) for i in range(36))


def encoder_odometry(robot: TricycleRobot) -> Tuple[Vec3, Quat, Vec3, Vec3]:
    """publishOdometry with odometrySource encoder: UpdateOdometryEncoder's pose (z 0) and twist (odometry-frame
    dx/dt, dy/dt and the yaw rate)."""
    odometry = robot.odometry
    half = odometry.yaw / 2
    linear = (odometry.linear[0], odometry.linear[1], 0.0)
    return (
        (odometry.x, odometry.y, 0.0),
        (0.0, 0.0, math.sin(half), math.cos(half)),
        linear,
        (0.0, 0.0, odometry.angular),
    )


class TricycleInterface(GazeboDriveInterface):
    def __init__(
        self, name: str, robot: TricycleRobot, sim: Simulation, tf: Optional[PackedPublisher], namespace: str
    ) -> None:
        config = robot.config
        super().__init__(name, robot, sim, tf, namespace, config.update_rate, POSE_COVARIANCE)  # type: ignore
        prefix = self.frame_prefix
        self._encoder_odometry = config.odometry_source == "encoder"
        joints = config.joints_needed
        links = robot.model.robot.joints
        # publishWheelTF: the joint's parent link -> a frame named after the joint, at the child link's pose in the
        # model's frame (Link::RelativePose).
        self._wheel_tf: List[Tuple[str, TransformPacker]] = [
            (
                links[joint].child,
                TransformPacker(resolve_frame(prefix, links[joint].parent), resolve_frame(prefix, joint)),
            )
            for joint in joints
        ]
        self._joint_pub: Optional[PackedPublisher] = None
        if config.publish_wheel_joint_state:
            self._joint_pub = packed_publisher(plugin_topic(namespace, "joint_states"), JointState)
        self._joint_packer = JointStatePacker(list(joints), zero_efforts=True)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        secs, nsecs = stamp.secs, stamp.nsecs
        robot = self.robot
        odometry = encoder_odometry(robot) if self._encoder_odometry else yaw_frame_odometry(robot.model)
        position, orientation, linear, angular = odometry
        self._odom_pub.publish(self._odom_packer.pack, secs, nsecs, position, orientation, linear, angular)
        if self._tf is not None:
            self._tf.publish(self._tf_packer.pack, secs, nsecs, position, orientation)
            if self.robot.config.publish_wheel_tf:
                model = self.robot.model
                back = inverse(model.model_transform())
                for child, packer in self._wheel_tf:
                    translation, (w, x, y, z) = compose(back, model.link_transform(child))
                    self._tf.publish(packer.pack, secs, nsecs, translation, (x, y, z, w))
        if self._joint_pub is not None:
            joints = self.robot.wheels
            positions = tuple(joint.angle() for joint in joints)
            self._joint_pub.publish(self._joint_packer.pack, secs, nsecs, positions, tuple(j.rate() for j in joints))

    def close(self) -> None:
        super().close()
        if self._joint_pub is not None:
            release(self._joint_pub)


def interfaces(context: ModelContext, config: TricycleConfig) -> List[Periodic]:
    return gazebo_drive_interfaces(context, config, TricycleRobot, TricycleInterface)
