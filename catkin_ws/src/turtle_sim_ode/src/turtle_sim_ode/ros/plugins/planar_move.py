"""gazebo_ros_planar_move's topics (world.plugins.planar_move), as GazeboRosPlanarMove has them: ``commandTopic``
(geometry_msgs/Twist: linear.x, linear.y, angular.z) in; ``odometryTopic`` (nav_msgs/Odometry) and tf
``odometryFrame`` -> ``robotBaseFrame`` out at ``odometryRate`` (publishOdometry: the model's pose, z 0; twist from
the pose's change since the last message in the yaw frame; pose covariance 1e-5, 1e-5, 1e12 x3, 1e-3)."""
from __future__ import annotations

import math
from typing import List, Optional, Tuple

import rospy
from geometry_msgs.msg import Twist

from turtle_sim_ode.models.transforms import rpy_of
from turtle_sim_ode.ros.periodic import ModelContext, Periodic
from turtle_sim_ode.ros.plugins.drive import GazeboDriveInterface, gazebo_drive_interfaces
from turtle_sim_ode.ros.throttle import logwarn_every
from turtle_sim_ode.ros.wire import PackedPublisher
from turtle_sim_ode.world.plugins.planar_move import PlanarMoveConfig, PlanarMoveRobot
from turtle_sim_ode.world.simulation import Simulation

POSE_COVARIANCE = tuple({0: 1e-5, 7: 1e-5, 14: 1e12, 21: 1e12, 28: 1e12, 35: 1e-3}.get(i, 0.0) for i in range(36))


class PlanarMoveInterface(GazeboDriveInterface):
    def __init__(
        self, name: str, robot: PlanarMoveRobot, sim: Simulation, tf: Optional[PackedPublisher], namespace: str
    ) -> None:
        rate = robot.config.odometry_rate
        super().__init__(name, robot, sim, tf, namespace, rate, POSE_COVARIANCE)  # type: ignore[arg-type]
        self._last: Optional[Tuple[float, float, float, float]] = None  # time, x, y, yaw of the last message
        self._publishes = rate > 0  # odometryRate 0: no odometry, as UpdateChild

    def _on_velocity(self, twist: Twist) -> None:
        x, y, rotation = twist.linear.x, twist.linear.y, twist.angular.z
        if not self.robot.drive.set_command(x, y, rotation, self._sim.sim_time):
            logwarn_every(
                5.0,
                self.name + "/not_finite",
                "%s: velocity command ignored, not finite: linear.x [%s] linear.y [%s] angular.z [%s]"
                % (self.name, x, y, rotation),
            )

    def restart(self, now: float) -> None:
        super().restart(now)
        self._last = None

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not self._publishes:
            return
        model = self.robot.model
        position, orientation = model.link_pose(model.root_link)
        x, y, z, w = orientation
        yaw = rpy_of((w, x, y, z))[2]
        linear, angular = (0.0, 0.0, 0.0), 0.0
        if self._last is not None and now > self._last[0]:
            step = now - self._last[0]
            vx, vy = (position[0] - self._last[1]) / step, (position[1] - self._last[2]) / step
            linear = (math.cos(yaw) * vx + math.sin(yaw) * vy, math.cos(yaw) * vy - math.sin(yaw) * vx, 0.0)
            rotation = self.robot.drive.command[2]
            if rotation > math.pi / step:  # too fast to tell from two yaws: the command, as publishOdometry
                angular = rotation
            else:
                angular = ((yaw - self._last[3] + math.pi) % math.tau - math.pi) / step
        self._last = (now, position[0], position[1], yaw)
        secs, nsecs = stamp.secs, stamp.nsecs
        planar = (position[0], position[1], 0.0)
        self._odom_pub.publish(self._odom_packer.pack, secs, nsecs, planar, orientation, linear, (0.0, 0.0, angular))
        if self._tf is not None:
            self._tf.publish(self._tf_packer.pack, secs, nsecs, position, orientation)


def interfaces(context: ModelContext, config: PlanarMoveConfig) -> List[Periodic]:
    return gazebo_drive_interfaces(context, config, PlanarMoveRobot, PlanarMoveInterface)
