"""The ROS side of the gazebo_ros plugins a model carries: drive, ground truth (p3d), joint state publisher.

Each publisher keeps its own schedule in sim time; SimulatorNode calls publish_due() after every step.
"""
from __future__ import annotations

import math
import random
from typing import Dict, List, Optional, Sequence, Tuple

import ode
import rospy
from gazebo_msgs.msg import ContactsState, ContactState
from geometry_msgs.msg import Point, Twist, Vector3, Wrench
from kobuki_msgs.msg import BumperEvent, CliffEvent
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, JointState, LaserScan
from std_msgs.msg import Empty as EmptyMsg

from turtle_sim_ode.models.builder import BuiltModel, quat_from_rpy, quat_multiply
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.ros.camera_topics import CameraPublisher
from turtle_sim_ode.ros.periodic import (
    Advertising,
    Periodic,
    TopicCheck,
    packed_publisher,
    plugin_topic,
    publisher,
    subscriber,
    topic_prefix,
)
from turtle_sim_ode.ros.settings import SimulatorSettings
from turtle_sim_ode.ros.throttle import logwarn_every
from turtle_sim_ode.ros.wire import (
    ImuPacker,
    JointStatePacker,
    LaserScanPacker,
    OdometryPacker,
    PackedPublisher,
    Quat,
    TransformPacker,
    release,
)
from turtle_sim_ode.sensors.camera import CameraSensor
from turtle_sim_ode.sensors.config import ContactConfig, ImuConfig
from turtle_sim_ode.sensors.imu import ImuSensor
from turtle_sim_ode.sensors.kobuki import BumperSensor, CliffSensor
from turtle_sim_ode.sensors.laser import LaserScanner
from turtle_sim_ode.world.plugins import GroundTruthConfig, JointStatesConfig, find_body
from turtle_sim_ode.world.robot import DiffDriveRobot
from turtle_sim_ode.world.simulation import Simulation

# Diagonal covariances as the Kobuki driver reports them: x, y and yaw measured, the rest unknown.
ODOM_POSE_COVARIANCE = [
    0.1,
    0,
    0,
    0,
    0,
    0,
    0,
    0.1,
    0,
    0,
    0,
    0,
    0,
    0,
    1e6,
    0,
    0,
    0,
    0,
    0,
    0,
    1e6,
    0,
    0,
    0,
    0,
    0,
    0,
    1e6,
    0,
    0,
    0,
    0,
    0,
    0,
    0.05,
]
ODOM_TWIST_COVARIANCE = ODOM_POSE_COVARIANCE
# gazebo_ros_diff_drive's /odom (GazeboRosDiffDrive::publishOdometry, either odometrySource): x, y and yaw
# measured, z, roll and pitch unknown; no twist covariance.
DIFF_DRIVE_POSE_COVARIANCE = tuple(
    {0: 1e-5, 7: 1e-5, 14: 1e12, 21: 1e12, 28: 1e12, 35: 1e-3}.get(index, 0.0) for index in range(36)
)
DIFF_DRIVE_TWIST_COVARIANCE = (0.0,) * 36
# The frame kobuki_gazebo_plugins stamps /joint_states with (resolved with the tf_prefix).
KOBUKI_JOINT_STATES_FRAME = "base_link"
Vec3 = Tuple[float, float, float]


def period(rate: float) -> float:
    """Seconds of sim time between messages at ``rate`` Hz; rate 0 means every step, as in Gazebo."""
    return 1.0 / rate if rate > 0 else 0.0


def rotate_inverse(q: Sequence[float], v: Sequence[float]) -> Vec3:
    """Rotate vector v by the inverse of unit quaternion q (x, y, z, w): world axes to body axes."""
    x, y, z, w = -q[0], -q[1], -q[2], q[3]
    vx, vy, vz = v
    tx, ty, tz = 2 * (y * vz - z * vy), 2 * (z * vx - x * vz), 2 * (x * vy - y * vx)
    return (vx + w * tx + y * tz - z * ty, vy + w * ty + z * tx - x * tz, vz + w * tz + x * ty - y * tx)


def tf_prefix(namespace: str) -> str:
    """The tf_prefix gazebo_plugins' GazeboRos (diff drive, Kobuki) gives a plugin in ``namespace``: the
    ``tf_prefix`` parameter searched upwards from the namespace, else the namespace itself without its trailing
    slash."""
    parts = [part for part in namespace.strip("/").split("/") if part]
    for depth in range(len(parts), -1, -1):
        key = "/" + "/".join(parts[:depth] + ["tf_prefix"])
        if rospy.has_param(key):
            return str(rospy.get_param(key))
    return namespace.rstrip("/")


def resolve_frame(prefix: str, frame: str) -> str:
    """tf::resolve: a frame with a leading slash as it is (without the slash), else under ``prefix``."""
    if frame.startswith("/"):
        return frame[1:]
    prefix = prefix.lstrip("/")
    return f"{prefix}/{frame}" if prefix else frame


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
        prefix_tf = tf_prefix(namespace or config.robot_namespace)
        base_frame = config.base_frame or settings.base_frame
        self._base_frame = base_frame.lstrip("/")  # the link; a leading "/" only keeps the tf_prefix off
        self._odom_frame = resolve_frame(prefix_tf, config.odometry_frame or settings.odom_frame)
        published_base = resolve_frame(prefix_tf, base_frame)
        self._world_odometry = config.odometry_source == "world"
        self._reset_requested = False
        prefix = topic_prefix(namespace or config.robot_namespace)
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
        linear, angular = twist.linear.x, twist.angular.z
        if not self.robot.drive.set_command(linear, angular, self._sim.sim_time):
            logwarn_every(
                5.0,
                self.name + "/not_finite",
                "%s: velocity command ignored, not finite: linear.x [%s] angular.z [%s]" % (self.name, linear, angular),
            )
        elif abs(linear) > self.robot.params.max_linear or abs(angular) > self.robot.params.max_angular:
            logwarn_every(
                5.0,
                self.name + "/clamped",
                "%s: velocity command clamped: linear.x [%s] angular.z [%s] to max_linear [%s] max_angular [%s]"
                % (self.name, linear, angular, self.robot.params.max_linear, self.robot.params.max_angular),
            )

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
        if self._joint_pub is not None and self._joint_pub.get_num_connections():
            left, right = self.robot.left, self.robot.right
            self._joint_pub.publish(
                self._joint_packer.pack, secs, nsecs, (left.angle(), right.angle()), (left.rate(), right.rate())
            )

    def close(self) -> None:
        for handle in self._handles:
            release(handle)


class GroundTruthPublisher(Periodic):
    """A link's true pose and velocity as nav_msgs/Odometry, published only while subscribed.

    p3d (`twist_in_body` false) gives the twist in the world frame as gazebo_ros_p3d does; the simulator's own
    ground truth gives it in the body frame, as nav_msgs/Odometry asks."""

    def __init__(
        self,
        model: BuiltModel,
        link: str,
        topic: str,
        frame: str,
        rate: float,
        twist_in_body: bool,
        noise: float = 0.0,
        xyz_offset: Vec3 = (0.0, 0.0, 0.0),
        rpy_offset: Vec3 = (0.0, 0.0, 0.0),
    ) -> None:
        super().__init__(period(rate))
        self._model = model
        self._link = link
        self._twist_in_body = twist_in_body
        self._noise = noise
        self._offset = xyz_offset
        w, x, y, z = quat_from_rpy(*rpy_offset)
        self._rotation_offset = (w, x, y, z)
        self._pub = packed_publisher(topic, Odometry)
        self._packer = OdometryPacker(frame, link)

    @classmethod
    def from_p3d(
        cls, model: BuiltModel, link: str, config: GroundTruthConfig, namespace: str, default_rate: float
    ) -> "GroundTruthPublisher":
        return cls(
            model,
            link,
            topic_prefix(namespace or config.robot_namespace) + config.topic,
            config.frame,
            config.update_rate,  # 0: every step, as gazebo_ros_p3d
            False,
            config.gaussian_noise,
            config.xyz_offset,
            config.rpy_offset,
        )

    def _noisy(self, values: Sequence[float]) -> Vec3:
        if not self._noise:
            return tuple(values)  # type: ignore[return-value]
        return tuple(v + random.gauss(0.0, self._noise) for v in values)  # type: ignore[return-value]

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not self._pub.get_num_connections():
            return
        (px, py, pz), (w, x, y, z) = self._model.link_transform(self._link)
        linear, angular = self._model.link_twist(self._link)
        ow, ox, oy, oz = quat_multiply(self._rotation_offset, (w, x, y, z))
        position = self._noisy((px + self._offset[0], py + self._offset[1], pz + self._offset[2]))
        if self._twist_in_body:
            linear, angular = rotate_inverse((x, y, z, w), linear), rotate_inverse((x, y, z, w), angular)
        linear = self._noisy(linear)
        angular = self._noisy(angular)
        self._pub.publish(self._packer.pack, stamp.secs, stamp.nsecs, position, (ox, oy, oz, ow), linear, angular)

    def close(self) -> None:
        release(self._pub)


class JointStatePublisher(Periodic):
    """libgazebo_ros_joint_state_publisher.so: positions and velocities of the named joints."""

    def __init__(self, model: BuiltModel, config: JointStatesConfig, namespace: str) -> None:
        super().__init__(period(config.update_rate))
        self._handles = [model.joint(name) for name in config.joints]
        self._packer = JointStatePacker(list(config.joints))
        self._pub = packed_publisher(topic_prefix(namespace or config.robot_namespace) + "joint_states", JointState)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not self._pub.get_num_connections():
            return
        handles = self._handles
        positions = [handle.angle() for handle in handles]
        velocities = [handle.rate() for handle in handles]
        self._pub.publish(self._packer.pack, stamp.secs, stamp.nsecs, positions, velocities)

    def close(self) -> None:
        release(self._pub)


class LaserPublisher(Periodic):
    """sensor_msgs/LaserScan of a ray sensor; rays are cast only when due and someone listens."""

    def __init__(self, scanner: LaserScanner, namespace: str, time_step: float) -> None:
        config = scanner.config
        super().__init__(period(config.update_rate))  # 0: every step, as Gazebo's sensors
        self._scanner = scanner
        self._pub = packed_publisher(plugin_topic(namespace or config.robot_namespace, config.topic), LaserScan)
        # gazebo_ros_laser resolves its frameName with the tf_prefix as GazeboRos does (tf_prefix, else namespace).
        self._packer = LaserScanPacker(
            resolve_frame(tf_prefix(namespace or config.robot_namespace), scanner.frame),
            angle_min=config.min_angle,
            angle_max=config.max_angle,
            angle_increment=config.angle_increment,
            time_increment=0.0,
            scan_time=period(config.update_rate) or time_step,
            range_min=config.range_min,
            range_max=config.range_max,
            beams=config.samples,
        )

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not self._pub.get_num_connections():
            return
        self._pub.publish(self._packer.pack, stamp.secs, stamp.nsecs, self._scanner.scan())

    def close(self) -> None:
        release(self._pub)


class ImuPublisher(Periodic):
    """sensor_msgs/Imu of a link: the Kobuki's gyro, or an IMU plugin's (libgazebo_ros_imu*.so)."""

    def __init__(self, sensor: ImuSensor, topic: str, frame: str, rate: float) -> None:
        super().__init__(period(rate))  # rate 0: every step, as gazebo_plugins has it
        self._sensor = sensor
        self._pub = packed_publisher(topic, Imu)
        self._packer = ImuPacker(frame)

    def restart(self, now: float) -> None:
        super().restart(now)
        self._sensor.reset()  # a world or time reset is a jump the acceleration must not see

    def publish(self, stamp: rospy.Time, now: float) -> None:
        reading = self._sensor.read(now)  # every time, even unheard: acceleration differences need each reading
        self._pub.publish(
            self._packer.pack,
            stamp.secs,
            stamp.nsecs,
            reading.orientation,
            reading.orientation_covariance,
            reading.angular_velocity,
            reading.angular_velocity_covariance,
            reading.linear_acceleration,
            reading.linear_acceleration_covariance,
        )

    def close(self) -> None:
        release(self._pub)


class BumperEventPublisher(Periodic):
    """The Kobuki plugin's bumper events: one kobuki_msgs/BumperEvent per change."""

    def __init__(self, sensor: BumperSensor, topic: str, rate: float) -> None:
        super().__init__(period(rate))
        self._sensor = sensor
        self._pub = publisher(topic, BumperEvent, 10)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        for bumper, state in self._sensor.changes():  # every time, even unheard: events are changes
            self._pub.publish(BumperEvent(bumper=bumper, state=state))

    def close(self) -> None:
        self._sensor.close()
        release(self._pub)


class CliffEventPublisher(Periodic):
    """The Kobuki plugin's cliff events: one kobuki_msgs/CliffEvent per change, with the distance to
    the floor in cm (``bottom``; the ray's range when it sees nothing)."""

    def __init__(self, sensor: CliffSensor, topic: str, rate: float) -> None:
        super().__init__(period(rate))
        self._sensor = sensor
        self._pub = publisher(topic, CliffEvent, 10)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        for sensor, state, distance in self._sensor.changes():
            bottom = int(round(min(distance, self._sensor.max_range) * 100.0))
            self._pub.publish(CliffEvent(sensor=sensor, state=state, bottom=bottom))

    def close(self) -> None:
        release(self._pub)


class ContactsPublisher(Periodic):
    """libgazebo_ros_bumper.so: gazebo_msgs/ContactsState of a link's collisions during the last step, one
    ContactState per touching pair with Gazebo's scoped collision names. Contact forces are not measured:
    wrenches are zero."""

    GROUND = "ground_plane::link::collision"

    def __init__(self, sim: Simulation, model: BuiltModel, config: ContactConfig, namespace: str) -> None:
        super().__init__(period(config.update_rate))
        self._pub = publisher(plugin_topic(namespace or config.robot_namespace, config.topic), ContactsState, 1)
        self._sim = sim
        self._physics: PhysicsWorld = sim.physics
        self._watch = self._physics.watch_contacts(model.geoms.get(config.link, []))
        self._frame = config.frame
        self._names: Dict[ode.GeomObject, str] = {}

    def _name(self, geom: ode.GeomObject) -> str:
        if geom is self._physics.ground:
            return self.GROUND
        if geom not in self._names:  # a model spawned since: name every geom again
            self._names = {
                g: "%s::%s::%s_collision%s" % (model.name, link, link, "_%d" % i if i else "")
                for model in self._sim.models.values()
                for link, geoms in model.geoms.items()
                for i, g in enumerate(geoms)
            }
        return self._names.get(geom, "unknown")

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not self._pub.get_num_connections():
            return
        pairs: Dict[Tuple[ode.GeomObject, ode.GeomObject], ContactState] = {}
        for contact in self._watch.contacts:
            state = pairs.get((contact.geom, contact.other))
            if state is None:
                state = pairs[(contact.geom, contact.other)] = ContactState(
                    collision1_name=self._name(contact.geom), collision2_name=self._name(contact.other)
                )
                state.info = "%s touches %s" % (state.collision1_name, state.collision2_name)
            state.contact_positions.append(Point(*contact.position))
            state.contact_normals.append(Vector3(*contact.normal))
            state.depths.append(contact.depth)
            state.wrenches.append(Wrench())
        message = ContactsState(states=list(pairs.values()))
        message.header.stamp = stamp
        message.header.frame_id = self._frame
        self._pub.publish(message)

    def close(self) -> None:
        self._physics.unwatch_contacts(self._watch)
        release(self._pub)


def _imupublisher(model: BuiltModel, config: ImuConfig, gravity: Vec3, namespace: str) -> Optional[Periodic]:
    if config.link not in model.links:
        rospy.logwarn("model %s: IMU link [%s] does not exist: not published", model.name, config.link)
        return None
    topic = plugin_topic(namespace or config.robot_namespace, config.topic)
    sensor = ImuSensor(model, config.link, gravity, config.noise)
    return ImuPublisher(sensor, topic, config.frame or config.link, config.update_rate)


def _kobuki_events(
    sim: Simulation, model: BuiltModel, robot: DiffDriveRobot, prefix: str, settings: SimulatorSettings
) -> List[Periodic]:
    """The Kobuki plugin's bumper and cliff events; its bumper and cliff sensors sit on base_link (kobuki_description),
    else on the root link."""
    link = "base_link" if model.geoms.get("base_link") else model.root_link
    if not model.geoms.get(link):
        rospy.logwarn("model %s: no collision geoms on [%s]: no bumper or cliff events", model.name, link)
        return []
    bumper = BumperSensor(sim.physics, model, link)
    events: List[Periodic] = []
    try:
        events.append(BumperEventPublisher(bumper, prefix + "bumper", settings.publish_rate))
        cliff = CliffSensor(sim.physics, model, link, robot.config.cliff_threshold)
        events.append(CliffEventPublisher(cliff, prefix + "cliff", settings.publish_rate))
    except BaseException:
        bumper.close()  # its contact watch: the publisher that would close it was refused
        raise
    return events


def model_interfaces(
    name: str,
    sim: Simulation,
    settings: SimulatorSettings,
    tf_broadcaster: PackedPublisher,
    namespace: str,
    check_topic: Optional[TopicCheck] = None,
) -> List[Periodic]:
    """Every ROS publisher and subscriber the plugins of model `name` ask for (call under the world lock), each
    topic first shown to ``check_topic``. All or nothing: if one fails, those opened so far are closed again."""
    interfaces: List[Periodic] = []
    Advertising.check, Advertising.opened = check_topic, []
    try:
        _add_interfaces(name, sim, settings, tf_broadcaster, namespace, interfaces)
    except BaseException:
        for interface in interfaces:
            interface.close()
        for handle in Advertising.opened:  # those of an interface that failed half-way
            release(handle)
        raise
    finally:
        Advertising.check, Advertising.opened = None, []
    return interfaces


def _add_interfaces(
    name: str,
    sim: Simulation,
    settings: SimulatorSettings,
    tf_broadcaster: PackedPublisher,
    namespace: str,
    interfaces: List[Periodic],
) -> None:
    model = sim.models[name]
    robot = sim.robots.get(name)
    if robot is not None:
        interfaces.append(DriveInterface(name, robot, settings, tf_broadcaster, sim, namespace))
        if robot.config.filename.endswith("kobuki.so"):
            # turtlebot_gazebo's ground-truth odometry of the base, under the node's parameters.
            base = settings.base_frame if settings.base_frame in model.links else model.root_link
            interfaces.append(
                GroundTruthPublisher(
                    model,
                    base,
                    topic_prefix(namespace) + settings.ground_truth_topic,
                    settings.ground_truth_frame,
                    settings.publish_rate,
                    True,
                )
            )
            # The Kobuki plugin's gyro, on <model>/sensors/imu_data as kobuki_gazebo_plugins publishes it.
            imu_link = "imu_link" if "imu_link" in model.links else base
            imu = ImuSensor(model, imu_link, tuple(sim.physics.params.gravity))
            interfaces.append(
                ImuPublisher(imu, topic_prefix(namespace) + name + "/sensors/imu_data", imu_link, settings.publish_rate)
            )
            interfaces += _kobuki_events(sim, model, robot, topic_prefix(namespace) + name + "/events/", settings)
    plugins = sim.plugins.get(name)
    if plugins is not None:
        for config in plugins.ground_truths:
            link = find_body(list(model.links), config.body)
            if link is None:
                rospy.logwarn("model %s: p3d bodyName [%s] is not a link: not published", name, config.body)
                continue
            interfaces.append(GroundTruthPublisher.from_p3d(model, link, config, namespace, settings.publish_rate))
        for config in plugins.joint_states:
            interfaces.append(JointStatePublisher(model, config, namespace))
        for config in plugins.lasers:
            scanner = LaserScanner(sim.physics, model, config.link, config)
            interfaces.append(LaserPublisher(scanner, namespace, sim.physics.time_step))
        for config in plugins.imus:
            publisher = _imupublisher(model, config, tuple(sim.physics.params.gravity), namespace)
            if publisher is not None:
                interfaces.append(publisher)
        for config in plugins.contacts:
            interfaces.append(ContactsPublisher(sim, model, config, namespace))
        for config in plugins.cameras:
            sensor = CameraSensor(sim.physics, model, config, sun_direction=sim.light_direction, sky=sim.sky_colour)
            interfaces.append(CameraPublisher(sensor, sim.scene, namespace))
