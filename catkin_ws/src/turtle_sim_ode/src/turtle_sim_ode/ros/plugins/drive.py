"""The ROS side the drive plugins share (gazebo_ros_diff_drive, the Kobuki): velocity commands in; odometry, tf
and wheel joint states out, with one stamp."""
from __future__ import annotations

import math
from typing import List, Optional, Sequence, Tuple

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState
from std_msgs.msg import Empty as EmptyMsg

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, plugin_topic, subscriber, topic_prefix
from turtle_sim_ode.ros.plugin_topics import (
    DIFF_DRIVE_POSE_COVARIANCE,
    DIFF_DRIVE_TWIST_COVARIANCE,
    KOBUKI_JOINT_STATES_FRAME,
    ODOM_POSE_COVARIANCE,
    ODOM_TWIST_COVARIANCE,
    Vec3,
    period,
    resolve_frame,
    rotate_inverse,
    tf_prefix,
)
from turtle_sim_ode.ros.settings import SimulatorSettings
from turtle_sim_ode.ros.throttle import logwarn_every
from turtle_sim_ode.ros.wire import JointStatePacker, OdometryPacker, PackedPublisher, Quat, TransformPacker, release
from turtle_sim_ode.world.plugins import DiffDriveRobot, DriveRobot
from turtle_sim_ode.world.simulation import Simulation


def command_drive(name: str, robot: DriveRobot, twist: Twist, now: float) -> None:
    """A Twist's linear.x and angular.z to ``robot``'s drive; throttled warnings for a command not finite (ignored)
    or beyond the drive's limits (clamped)."""
    linear, angular = twist.linear.x, twist.angular.z
    params = robot.params
    if not robot.drive.set_command(linear, angular, now):
        logwarn_every(
            5.0,
            name + "/not_finite",
            "%s: velocity command ignored, not finite: linear.x [%s] angular.z [%s]" % (name, linear, angular),
        )
    elif abs(linear) > params.max_linear or abs(angular) > params.max_angular:
        logwarn_every(
            5.0,
            name + "/clamped",
            "%s: velocity command clamped: linear.x [%s] angular.z [%s] to max_linear [%s] max_angular [%s]"
            % (name, linear, angular, params.max_linear, params.max_angular),
        )


class GazeboDriveInterface(Periodic):
    """What gazebo_plugins' skid steer, planar move and tricycle drives share: ``commandTopic`` in, ``odometryTopic``
    out and tf ``odometryFrame`` -> ``robotBaseFrame`` (``tf`` None: none), both frames under the ``tf_prefix``
    parameter if one is set (tf::getPrefixParam). Subclasses publish, and may take the command otherwise."""

    def __init__(
        self,
        name: str,
        robot: DriveRobot,
        sim: Simulation,
        tf: Optional[PackedPublisher],
        namespace: str,
        rate: float,
        pose_covariance: Sequence[float],
        twist_covariance: Sequence[float] = (0.0,) * 36,
    ) -> None:
        config = robot.config
        super().__init__(period(rate))
        self.name = name
        self.robot = robot
        self._sim = sim
        self._tf = tf
        self.frame_prefix = tf_prefix(namespace, otherwise="")
        odom_frame = resolve_frame(self.frame_prefix, config.odometry_frame)  # type: ignore[attr-defined]
        base_frame = resolve_frame(self.frame_prefix, config.base_frame)  # type: ignore[attr-defined]
        command_topic = plugin_topic(namespace, config.command_topic)  # type: ignore[attr-defined]
        self._command = subscriber(command_topic, Twist, self._on_velocity, 1)
        self._odom_pub = packed_publisher(
            plugin_topic(namespace, config.odometry_topic), Odometry  # type: ignore[attr-defined]
        )
        self._odom_packer = OdometryPacker(odom_frame, base_frame, pose_covariance, twist_covariance)
        self._tf_packer = TransformPacker(odom_frame, base_frame)

    def _on_velocity(self, twist: Twist) -> None:
        command_drive(self.name, self.robot, twist, self._sim.sim_time)

    def close(self) -> None:
        release(self._command)
        release(self._odom_pub)


def yaw_frame_odometry(model: BuiltModel) -> Tuple[Vec3, Quat, Vec3, Vec3]:
    """The model's pose from the physics state (its canonical link's), and its twist as the skid steer's and the
    tricycle's publishOdometry give it: the world velocity's x and y turned into the yaw frame (z 0), and the
    world's yaw rate."""
    position, orientation = model.link_pose(model.root_link)
    linear, angular = model.link_twist(model.root_link)
    x, y, z, w = orientation
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    cos_yaw, sin_yaw = math.cos(yaw), math.sin(yaw)
    twist = (cos_yaw * linear[0] + sin_yaw * linear[1], cos_yaw * linear[1] - sin_yaw * linear[0], 0.0)
    return position, orientation, twist, (0.0, 0.0, angular[2])


def gazebo_drive_interfaces(
    context: ModelContext, config: object, robot_type: type, interface_type: type, broadcast_tf: bool = True
) -> List[Periodic]:
    """A GazeboDriveInterface for the model's drive robot if ``config`` is the one that made it (the first drive
    plugin; the others were warned about at spawn), with tf where ``broadcast_tf`` and the node publish it."""
    robot = context.sim.robots.get(context.name)
    if not isinstance(robot, robot_type) or robot.config is not config:
        return []
    tf = context.tf_broadcaster if broadcast_tf and context.settings.publish_tf else None
    return [interface_type(context.name, robot, context.sim, tf, context.namespace)]


class DriveInterface(Periodic):
    """A drive plugin's topics: velocity commands (and reset for the Kobuki) in; odometry, tf and wheel
    joint states out, with one stamp."""

    def __init__(
        self,
        name: str,
        robot: DiffDriveRobot,
        settings: SimulatorSettings,
        tf_broadcaster: PackedPublisher,
        sim: Simulation,
        namespace: str,
    ) -> None:
        config = robot.config
        # The Kobuki plugin publishes at the node's publish_rate; gazebo_ros_diff_drive's updateRate 0 is every step.
        kobuki = config.filename.endswith("kobuki.so")
        super().__init__(period(settings.publish_rate if kobuki else config.update_rate))
        self.name = name
        self.robot = robot
        self._sim = sim
        self._tf = tf_broadcaster if config.publish_tf and settings.publish_tf else None
        prefix_tf = tf_prefix(namespace)
        base_frame = config.base_frame or settings.base_frame
        self._base_frame = base_frame.lstrip("/")  # the link; a leading "/" only keeps the tf_prefix off
        self._odom_frame = resolve_frame(prefix_tf, config.odometry_frame or settings.odom_frame)
        published_base = resolve_frame(prefix_tf, base_frame)
        self._world_odometry = config.odometry_source == "world"
        self._reset_requested = False
        prefix = topic_prefix(namespace)
        self._handles: List = [subscriber(prefix + config.command_topic, Twist, self._on_velocity, 1)]
        if config.reset_topic:
            self._handles.append(subscriber(prefix + config.reset_topic, EmptyMsg, self._on_reset, 1))
        self._odom_pub = packed_publisher(prefix + config.odometry_topic, Odometry)
        if kobuki:
            covariances = (ODOM_POSE_COVARIANCE, ODOM_TWIST_COVARIANCE)
        else:
            covariances = (DIFF_DRIVE_POSE_COVARIANCE, DIFF_DRIVE_TWIST_COVARIANCE)
        self._odom_packer = OdometryPacker(self._odom_frame, published_base, *covariances)
        self._tf_packer = TransformPacker(self._odom_frame, published_base)
        self._joint_pub: Optional[PackedPublisher] = None
        if config.publish_joint_states:
            self._joint_pub = packed_publisher(prefix + "joint_states", JointState)
        self._handles += [p for p in (self._odom_pub, self._joint_pub) if p is not None]
        self._joint_packer = JointStatePacker(
            [robot.left.name, robot.right.name], resolve_frame(prefix_tf, KOBUKI_JOINT_STATES_FRAME) if kobuki else ""
        )

    def _on_velocity(self, twist: Twist) -> None:
        command_drive(self.name, self.robot, twist, self._sim.sim_time)

    def _on_reset(self, _msg: EmptyMsg) -> None:
        self._reset_requested = True  # applied in the simulation thread, between steps

    def _odometry(self, now: float) -> Tuple[Vec3, Quat, Vec3, Vec3]:
        """Pose (position, quaternion xyzw) and body-frame twist (linear, angular) at ``now``; the encoder
        odometry is integrated (or reset) here, whether anyone listens or not."""
        if self._world_odometry:  # gazebo_ros_diff_drive's odometrySource world: the physics state
            model = self.robot.model
            base = self._base_frame if self._base_frame in model.links else model.root_link
            position, quaternion = model.link_pose(base)
            linear, angular = model.link_twist(base)
            return position, quaternion, rotate_inverse(quaternion, linear), rotate_inverse(quaternion, angular)
        if self._reset_requested:
            self._reset_requested = False
            self.robot.reset_odometry(now)
            rospy.loginfo("%s: odometry reset", self.name)
        else:
            self.robot.update_odometry(now)
        odometry = self.robot.odometry
        half_yaw = odometry.yaw / 2
        return (
            (odometry.x, odometry.y, 0.0),
            (0.0, 0.0, math.sin(half_yaw), math.cos(half_yaw)),
            (odometry.linear, 0.0, 0.0),
            (0.0, 0.0, odometry.angular),
        )

    def publish(self, stamp: rospy.Time, now: float) -> None:
        position, orientation, linear, angular = self._odometry(now)
        secs, nsecs = stamp.secs, stamp.nsecs
        self._odom_pub.publish(self._odom_packer.pack, secs, nsecs, position, orientation, linear, angular)
        if self._tf is not None:
            self._tf.publish(self._tf_packer.pack, secs, nsecs, position, orientation)
        if self._joint_pub is not None and self._joint_pub.heard():
            left, right = self.robot.left, self.robot.right
            self._joint_pub.publish(
                self._joint_packer.pack, secs, nsecs, (left.angle(), right.angle()), (left.rate(), right.rate())
            )

    def close(self) -> None:
        for handle in self._handles:
            release(handle)
