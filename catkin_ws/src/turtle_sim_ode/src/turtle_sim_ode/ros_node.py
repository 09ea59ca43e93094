"""The simulator's ROS interface: node `gazebo` stepping a Simulation and publishing what falls due.

Everything is stamped with the simulation's own time, which this node also publishes on /clock, so it never
waits on ROS time itself.
"""
from __future__ import annotations

import math
import os
import threading
import time
from typing import Dict, List

import rospkg
import rospy
import tf2_ros
from geometry_msgs.msg import Quaternion, TransformStamped, Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from std_msgs.msg import Empty as EmptyMsg

from .gazebo_api import GazeboApi
from .settings import SettingsError, SimulatorSettings, settings_from_params
from .sdf_model import parse_sdf_world
from .simulation import DiffDriveRobot, Simulation
from .urdf_model import ModelError

# Diagonal covariances as the Kobuki driver reports them: x, y and yaw measured, the rest unknown.
ODOM_POSE_COVARIANCE = [0.1, 0, 0, 0, 0, 0, 0, 0.1, 0, 0, 0, 0, 0, 0, 1e6, 0, 0, 0,
                        0, 0, 0, 1e6, 0, 0, 0, 0, 0, 0, 1e6, 0, 0, 0, 0, 0, 0, 0.05]
ODOM_TWIST_COVARIANCE = ODOM_POSE_COVARIANCE
GROUND_TRUTH_COVARIANCE = [0.0] * 36


def sim_stamp(seconds: float) -> rospy.Time:
    nanoseconds = int(round(seconds * 1e9))
    return rospy.Time(nanoseconds // 1000000000, nanoseconds % 1000000000)


def yaw_quaternion(yaw: float) -> Quaternion:
    return Quaternion(0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


class RobotInterface:
    """The ROS side of one drive plugin, named as turtlebot_gazebo names them for model <name>:
    <name>/commands/velocity and <name>/commands/reset_odometry in; odom, tf, joint_states and the
    ground-truth odometry out."""

    def __init__(self, name: str, robot: DiffDriveRobot, settings: SimulatorSettings,
                 tf_broadcaster: tf2_ros.TransformBroadcaster, clock: Simulation, robot_namespace: str = "") -> None:
        self.name = name
        self.robot = robot
        self._settings = settings
        self._tf = tf_broadcaster
        self._sim = clock
        self._reset_requested = False
        # A model's robot_namespace prefixes its plugin's topics, as gazebo_ros plugins do.
        prefix = robot_namespace.strip("/") + "/" if robot_namespace.strip("/") else ""
        self._cmd_sub = rospy.Subscriber(prefix + name + "/commands/velocity", Twist, self._on_velocity, queue_size=1)
        self._reset_sub = rospy.Subscriber(prefix + name + "/commands/reset_odometry", EmptyMsg, self._on_reset,
                                           queue_size=1)
        self._odom_pub = rospy.Publisher(prefix + "odom", Odometry, queue_size=10)
        self._joint_pub = rospy.Publisher(prefix + "joint_states", JointState, queue_size=10)
        self._truth_pub = rospy.Publisher(prefix + settings.ground_truth_topic, Odometry, queue_size=10)
        self._joint_names = [robot.left.name, robot.right.name]

    def _on_velocity(self, twist: Twist) -> None:
        if not self.robot.drive.set_command(twist.linear.x, twist.angular.z, self._sim.sim_time):
            rospy.logwarn_throttle(5.0, "%s: velocity command ignored, not finite: linear.x [%s] angular.z [%s]"
                                   % (self.name, twist.linear.x, twist.angular.z))

    def _on_reset(self, _msg: EmptyMsg) -> None:
        self._reset_requested = True  # applied in the simulation thread, between steps

    def publish(self, stamp: rospy.Time, now: float) -> None:
        """Read the encoders and publish odom, tf, joint states and ground truth, all with one stamp."""
        robot = self.robot
        if self._reset_requested:
            self._reset_requested = False
            robot.reset_odometry(now)
            rospy.loginfo("%s: odometry reset", self.name)
        else:
            robot.update_odometry(now)
        settings = self._settings
        odometry = robot.odometry

        odom = Odometry()
        odom.header.stamp = stamp
        odom.header.frame_id = settings.odom_frame
        odom.child_frame_id = settings.base_frame
        odom.pose.pose.position.x = odometry.x
        odom.pose.pose.position.y = odometry.y
        odom.pose.pose.orientation = yaw_quaternion(odometry.yaw)
        odom.pose.covariance = ODOM_POSE_COVARIANCE
        odom.twist.twist.linear.x = odometry.linear
        odom.twist.twist.angular.z = odometry.angular
        odom.twist.covariance = ODOM_TWIST_COVARIANCE
        self._odom_pub.publish(odom)

        if settings.publish_tf:
            transform = TransformStamped()
            transform.header = odom.header
            transform.child_frame_id = settings.base_frame
            transform.transform.translation.x = odometry.x
            transform.transform.translation.y = odometry.y
            transform.transform.rotation = odom.pose.pose.orientation
            self._tf.sendTransform(transform)

        joints = JointState()
        joints.header.stamp = stamp
        joints.name = self._joint_names
        joints.position = [robot.left.angle(), robot.right.angle()]
        joints.velocity = [robot.left.rate(), robot.right.rate()]
        self._joint_pub.publish(joints)

        if self._truth_pub.get_num_connections():
            self._truth_pub.publish(self._ground_truth(stamp))

    def _ground_truth(self, stamp: rospy.Time) -> Odometry:
        """The base frame's true pose in the world; twist in the base frame, as nav_msgs/Odometry asks."""
        model = self.robot.model
        base = self._settings.base_frame if self._settings.base_frame in model.links else model.root_link
        position, (qx, qy, qz, qw) = model.link_pose(base)
        linear, angular = model.link_twist(base)
        truth = Odometry()
        truth.header.stamp = stamp
        truth.header.frame_id = self._settings.ground_truth_frame
        truth.child_frame_id = base
        pose = truth.pose.pose
        pose.position.x, pose.position.y, pose.position.z = position
        pose.orientation = Quaternion(qx, qy, qz, qw)
        truth.pose.covariance = GROUND_TRUTH_COVARIANCE
        # world -> body: rotate by the inverse quaternion
        truth.twist.twist.linear.x, truth.twist.twist.linear.y, truth.twist.twist.linear.z = _rotate_inverse(
            (qx, qy, qz, qw), linear)
        truth.twist.twist.angular.x, truth.twist.twist.angular.y, truth.twist.twist.angular.z = _rotate_inverse(
            (qx, qy, qz, qw), angular)
        return truth

    def close(self) -> None:
        for handle in (self._cmd_sub, self._reset_sub, self._odom_pub, self._joint_pub, self._truth_pub):
            handle.unregister()


def _rotate_inverse(q, v):
    """Rotate vector v by the inverse of unit quaternion q (x, y, z, w)."""
    x, y, z, w = q
    x, y, z = -x, -y, -z
    vx, vy, vz = v
    # t = 2 * cross(q.xyz, v); v' = v + w * t + cross(q.xyz, t)
    tx, ty, tz = 2 * (y * vz - z * vy), 2 * (z * vx - x * vz), 2 * (x * vy - y * vx)
    return (vx + w * tx + y * tz - z * ty, vy + w * ty + z * tx - x * tz, vz + w * tz + x * ty - y * tx)


class SimulatorNode:
    """Owns the simulation, its clock and the ROS interfaces of the spawned robots."""

    def __init__(self, settings: SimulatorSettings) -> None:
        self.settings = settings
        max_update_rate = settings.real_time_factor / settings.physics.time_step
        self.sim = Simulation(settings.physics, settings.drive_overrides, max_update_rate)
        # Service calls and topic callbacks run in rospy's threads; the world changes only under this lock.
        self.lock = threading.Lock()
        self._unpaused = threading.Event()
        if not settings.paused:
            self._unpaused.set()
        self._clock_pub = rospy.Publisher("/clock", Clock, queue_size=10)
        self._tf = tf2_ros.TransformBroadcaster()
        self.interfaces: Dict[str, RobotInterface] = {}
        self.api = GazeboApi(self.sim, self.lock, self.add_interface, self._remove_interface, self._set_paused,
                             lambda: self.paused, settings.model_states_rate)

    # --- models -------------------------------------------------------------------------------------------
    def add_interface(self, name: str, robot_namespace: str) -> None:
        """The ROS side of a freshly spawned model's drive plugin, if it has one (called under the lock)."""
        if name in self.sim.robots:
            self.interfaces[name] = RobotInterface(name, self.sim.robots[name], self.settings, self._tf, self.sim,
                                                   robot_namespace)

    def _remove_interface(self, name: str) -> None:
        interface = self.interfaces.pop(name, None)
        if interface is not None:
            interface.close()

    def spawn_urdf(self, name: str, urdf: str, pose) -> List[str]:
        """Spawn a model at start-up; ModelError on a bad name or model."""
        with self.lock:
            warnings = self.sim.spawn_urdf(name, urdf, pose)
            self.add_interface(name, "")
        for warning in warnings:
            rospy.logwarn("spawn %s: %s", name, warning)
        rospy.loginfo("spawned model [%s] at x %.3f y %.3f z %.3f yaw %.3f", name, pose[0], pose[1], pose[2], pose[5])
        return warnings

    def _set_paused(self, paused: bool) -> None:
        if paused:
            self._unpaused.clear()
        else:
            self._unpaused.set()

    @property
    def paused(self) -> bool:
        return not self._unpaused.is_set()

    # --- main loop ----------------------------------------------------------------------------------------
    def run(self) -> None:
        """Step until shutdown, publishing /clock and the robots' topics when due in sim time, paced to the
        simulation's real-time factor (which /gazebo/set_physics_properties may change)."""
        clock_period = 1.0 / self.settings.pub_clock_frequency
        publish_period = 1.0 / self.settings.publish_rate
        now = self.sim.sim_time
        self._clock_pub.publish(Clock(sim_stamp(now)))
        next_clock, next_publish = now + clock_period, now + publish_period
        anchor_wall, anchor_sim = time.monotonic(), now
        while not rospy.is_shutdown():
            if not self._unpaused.is_set():
                self._unpaused.wait(0.1)
                anchor_wall, anchor_sim = time.monotonic(), self.sim.sim_time
                continue
            with self.lock:
                if self.sim.sim_time < now:  # /gazebo/reset_simulation: time starts again
                    now = self.sim.sim_time
                    next_clock, next_publish = now, now
                    anchor_wall, anchor_sim = time.monotonic(), now
                self.sim.step()
                now = self.sim.sim_time
                if now >= next_publish - 1e-9:
                    next_publish = max(next_publish + publish_period, now)
                    stamp = sim_stamp(now)
                    for interface in self.interfaces.values():
                        interface.publish(stamp, now)
                self.api.publish_states(now)
                rtf = self.sim.real_time_factor
            if now >= next_clock - 1e-9:
                next_clock = max(next_clock + clock_period, now)
                self._clock_pub.publish(Clock(sim_stamp(now)))
            if rtf > 0:
                delay = anchor_wall + (now - anchor_sim) / rtf - time.monotonic()
                if delay > 0:
                    time.sleep(delay)
                elif delay < -0.5:
                    # Cannot keep up: run as fast as possible without trying to catch up later.
                    anchor_wall, anchor_sim = time.monotonic(), now

    def close(self) -> None:
        for interface in self.interfaces.values():
            interface.close()


def resolve_world(world_name: str) -> str:
    """A world file given as a path, or by file name in this package's worlds/ (as Gazebo's worlds/x.world)."""
    if os.path.isfile(world_name):
        return world_name
    packaged = os.path.join(rospkg.RosPack().get_path("turtle_sim_ode"), "worlds", os.path.basename(world_name))
    if os.path.isfile(packaged):
        return packaged
    raise ModelError("world file '%s' not found (nor %s)" % (world_name, packaged))


def load_world(node: SimulatorNode, world_name: str) -> None:
    path = resolve_world(world_name)
    with open(path) as world_file:
        world = parse_sdf_world(world_file.read())
    with node.lock:
        warnings = node.sim.load_world(world)
        # The node's real_time_factor parameter (the launch argument) wins over the world's pacing.
        node.sim.max_update_rate = node.settings.real_time_factor / node.sim.physics.time_step
        for model in world.models:
            node.add_interface(model.name, "")
    for warning in warnings:
        rospy.logwarn("world %s: %s", path, warning)
    rospy.loginfo("loaded world [%s] from %s: models %s", world.name, path, [m.name for m in world.models])


def main() -> int:
    rospy.init_node("gazebo")
    try:
        settings = settings_from_params(rospy.get_param("~", {}))
    except SettingsError as error:
        rospy.logfatal(str(error))
        return 1
    node = SimulatorNode(settings)
    if settings.world_name:
        try:
            load_world(node, settings.world_name)
        except (ModelError, OSError) as error:
            rospy.logfatal("cannot load world [%s]: %s" % (settings.world_name, error))
            return 1
    if settings.spawn_model_name:
        urdf = rospy.get_param(settings.spawn_robot_description, None)
        if not isinstance(urdf, str):
            rospy.logfatal("parameter %s holds no URDF to spawn model [%s]"
                           % (rospy.resolve_name(settings.spawn_robot_description), settings.spawn_model_name))
            return 1
        try:
            node.spawn_urdf(settings.spawn_model_name, urdf, settings.spawn_pose)
        except ModelError as error:
            rospy.logfatal("cannot spawn model [%s]: %s" % (settings.spawn_model_name, error))
            return 1
    try:
        node.run()
    except rospy.ROSInterruptException:
        pass
    finally:
        node.close()
    return 0
