"""gazebo_ros_skid_steer_drive's topics (world.plugins.skid_steer_drive), as GazeboRosSkidSteerDrive has them:
``commandTopic`` (geometry_msgs/Twist: linear.x, angular.z) in; ``odometryTopic`` (nav_msgs/Odometry) out at
``updateRate``, whether anyone listens or not, and ``odometryFrame`` -> ``robotBaseFrame`` on tf if ``broadcastTF``.
The odometry is the model's pose from the physics state (publishOdometry: position x, y with z 0, the full
orientation; twist x, y in the yaw-rotated frame and the world's yaw rate), covariances from the tags."""
from __future__ import annotations

from typing import List, Optional, Tuple

import rospy

from turtle_sim_ode.ros.periodic import ModelContext, Periodic
from turtle_sim_ode.ros.plugins.drive import GazeboDriveInterface, gazebo_drive_interfaces, yaw_frame_odometry
from turtle_sim_ode.ros.wire import PackedPublisher
from turtle_sim_ode.world.plugins.skid_steer_drive import SkidSteerConfig, SkidSteerRobot
from turtle_sim_ode.world.simulation import Simulation

UNKNOWN = 1e12  # z, roll and pitch: publishOdometry's covariance of what it does not measure


def covariance(config: SkidSteerConfig) -> Tuple[float, ...]:
    """The 6x6 diagonal publishOdometry sets on pose and twist alike."""
    diagonal = (config.covariance_x, config.covariance_y, UNKNOWN, UNKNOWN, UNKNOWN, config.covariance_yaw)
    return tuple(diagonal[index // 6] if index % 7 == 0 else 0.0 for index in range(36))


class SkidSteerInterface(GazeboDriveInterface):
    def __init__(
        self, name: str, robot: SkidSteerRobot, sim: Simulation, tf: Optional[PackedPublisher], namespace: str
    ) -> None:
        rate, covariances = robot.config.update_rate, covariance(robot.config)
        super().__init__(name, robot, sim, tf, namespace, rate, covariances, covariances)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        position, orientation, linear, angular = yaw_frame_odometry(self.robot.model)
        secs, nsecs = stamp.secs, stamp.nsecs
        planar = (position[0], position[1], 0.0)
        self._odom_pub.publish(self._odom_packer.pack, secs, nsecs, planar, orientation, linear, angular)
        if self._tf is not None:
            self._tf.publish(self._tf_packer.pack, secs, nsecs, position, orientation)


def interfaces(context: ModelContext, config: SkidSteerConfig) -> List[Periodic]:
    return gazebo_drive_interfaces(
        context, config, SkidSteerRobot, SkidSteerInterface, broadcast_tf=config.broadcast_tf
    )
