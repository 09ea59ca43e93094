"""ekf_localization_node's ROS side: parameters, subscribers, tf, the periodic update; the filter is localizer.py."""
from __future__ import annotations

import functools
import re
import threading
from typing import Dict, Optional

import numpy as np
import rospy
import tf2_ros
from geometry_msgs.msg import AccelWithCovarianceStamped, PoseWithCovarianceStamped, TransformStamped
from geometry_msgs.msg import TwistWithCovarianceStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu
from std_srvs.srv import Empty, EmptyResponse

from robot_localization.ekf import ACCELERATION_SLICE, POSE_SLICE, TWIST_SLICE
from robot_localization.localizer import Estimate, Localizer
from robot_localization.params import Config, ConfigError, Sensor
from robot_localization.prepare import ImuData, PoseData, TwistData
from robot_localization.rotations import (
    Transform,
    compose,
    inverse,
    matrix_to_quaternion,
    quaternion_to_matrix,
    rpy_to_quaternion,
)
from robot_localization.srv import SetPose, SetPoseResponse, ToggleFilterProcessing, ToggleFilterProcessingResponse

WARNING_PERIOD = 5.0  # s between two warnings of one kind
NUMBERS = re.compile(r"[-+]?\d[\d.e+-]*")


def pose_data(header, pose_with_covariance) -> PoseData:
    p, q = pose_with_covariance.pose.position, pose_with_covariance.pose.orientation
    return PoseData(
        header.stamp.to_sec(), header.frame_id, (p.x, p.y, p.z), (q.x, q.y, q.z, q.w), pose_with_covariance.covariance
    )


def twist_data(header, frame_id: str, twist_with_covariance) -> TwistData:
    v, w = twist_with_covariance.twist.linear, twist_with_covariance.twist.angular
    return TwistData(
        header.stamp.to_sec(), frame_id, (v.x, v.y, v.z), (w.x, w.y, w.z), twist_with_covariance.covariance
    )


def imu_data(msg: Imu) -> ImuData:
    q, w, a = msg.orientation, msg.angular_velocity, msg.linear_acceleration
    return ImuData(
        msg.header.stamp.to_sec(),
        msg.header.frame_id,
        (q.x, q.y, q.z, q.w),
        msg.orientation_covariance,
        (w.x, w.y, w.z),
        msg.angular_velocity_covariance,
        (a.x, a.y, a.z),
        msg.linear_acceleration_covariance,
    )


def transform_message(transform: Transform, stamp: rospy.Time, parent: str, child: str) -> TransformStamped:
    message = TransformStamped()
    message.header.stamp, message.header.frame_id, message.child_frame_id = stamp, parent, child
    rotation, translation = transform
    message.transform.translation.x, message.transform.translation.y, message.transform.translation.z = translation
    q = message.transform.rotation
    q.x, q.y, q.z, q.w = matrix_to_quaternion(rotation)
    return message


class EkfNode:
    def __init__(self) -> None:
        try:
            self.config = Config(rospy.get_param("~", {}))
        except ConfigError as error:
            rospy.logfatal("ekf_localization_node: %s", error)
            raise SystemExit(1)
        for warning in self.config.warnings():
            rospy.logwarn(warning)
        self._last_warnings: Dict[str, float] = {}
        self.tf_buffer = tf2_ros.Buffer()
        self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)
        self.tf_broadcaster = tf2_ros.TransformBroadcaster()
        self.lock = threading.Lock()
        self.localizer = Localizer(self.config, self.lookup, rospy.Time.now().to_sec(), self.warn)
        self.localizer.use_sim_time = bool(rospy.get_param("/use_sim_time", False))
        self.odometry_publisher = rospy.Publisher("odometry/filtered", Odometry, queue_size=20)
        self.accel_publisher = (
            rospy.Publisher("accel/filtered", AccelWithCovarianceStamped, queue_size=20)
            if self.config.publish_acceleration
            else None
        )
        self.subscribers = [self.subscribe(sensor) for sensor in self.config.sensors if sensor.used]
        self.set_pose_subscriber = rospy.Subscriber("set_pose", PoseWithCovarianceStamped, self.on_set_pose)
        self.services = [
            rospy.Service("set_pose", SetPose, self.on_set_pose_service),
            rospy.Service("~enable", Empty, self.on_enable),
            rospy.Service("~toggle", ToggleFilterProcessing, self.on_toggle),
        ]
        if self.config.disabled_at_startup:
            rospy.loginfo("Filter is disabled. To enable it call the %s service", rospy.resolve_name("~enable"))
        self.timer = rospy.Timer(rospy.Duration(1.0 / self.config.frequency), self.on_timer)

    def subscribe(self, sensor: Sensor) -> rospy.Subscriber:
        message_type, callback = {
            "odom": (Odometry, self.on_odometry),
            "pose": (PoseWithCovarianceStamped, self.on_pose),
            "twist": (TwistWithCovarianceStamped, self.on_twist),
            "imu": (Imu, self.on_imu),
        }[sensor.kind]
        rospy.loginfo("%s: subscribed to %s", sensor.name, rospy.resolve_name(sensor.topic))
        return rospy.Subscriber(
            sensor.topic,
            message_type,
            functools.partial(callback, sensor),
            queue_size=sensor.queue_size,
            tcp_nodelay=sensor.nodelay,
        )

    # ---- inputs ----
    def on_odometry(self, sensor: Sensor, msg: Odometry) -> None:
        pose = pose_data(msg.header, msg.pose)
        twist = twist_data(msg.header, msg.child_frame_id, msg.twist)
        with self.lock:
            self.localizer.odometry(sensor, pose, twist, msg.child_frame_id)

    def on_pose(self, sensor: Sensor, msg: PoseWithCovarianceStamped) -> None:
        with self.lock:
            self.localizer.pose(sensor, pose_data(msg.header, msg.pose))

    def on_twist(self, sensor: Sensor, msg: TwistWithCovarianceStamped) -> None:
        with self.lock:
            self.localizer.twist(sensor, twist_data(msg.header, msg.header.frame_id, msg.twist))

    def on_imu(self, sensor: Sensor, msg: Imu) -> None:
        with self.lock:
            self.localizer.imu(sensor, imu_data(msg))

    def on_set_pose(self, msg: PoseWithCovarianceStamped) -> None:
        rospy.loginfo("Received set_pose request with value\n%s", msg)
        with self.lock:
            self.localizer.set_pose(pose_data(msg.header, msg.pose), rospy.Time.now().to_sec())

    def on_set_pose_service(self, request) -> SetPoseResponse:
        self.on_set_pose(request.pose)
        return SetPoseResponse()

    def on_enable(self, _request) -> EmptyResponse:
        with self.lock:
            if self.localizer.enabled:
                rospy.logwarn(
                    "Asking for enabling filter service, but the filter was already enabled! Use param "
                    "disabled_at_startup."
                )
            else:
                rospy.loginfo("Enabling filter...")
                self.localizer.enabled = True
        return EmptyResponse()

    def on_toggle(self, request) -> ToggleFilterProcessingResponse:
        with self.lock:
            if request.on == self.localizer.toggled_on:
                rospy.logwarn("Service was called to toggle filter processing but state was already as requested.")
                return ToggleFilterProcessingResponse(status=False)
            rospy.loginfo("Toggling filter measurement filtering to %s.", "On" if request.on else "Off")
            self.localizer.toggled_on = request.on
        return ToggleFilterProcessingResponse(status=True)

    # ---- tf ----
    def lookup(self, target: str, source: str, stamp: float) -> Optional[Transform]:
        """lookupTransformSafe: at the stamp, else the latest (with a warning); None where tf has nothing."""
        timeout = rospy.Duration(self.config.transform_timeout)
        try:
            message = self.tf_buffer.lookup_transform(target, source, rospy.Time.from_sec(stamp), timeout)
        except tf2_ros.TransformException:
            try:
                message = self.tf_buffer.lookup_transform(target, source, rospy.Time(0))
                self.warn(
                    "Transform from %s to %s was unavailable for the time requested. Using latest instead."
                    % (source, target)
                )
            except tf2_ros.TransformException as error:
                if target != source:
                    self.warn("Could not obtain transform from %s to %s. Error was %s" % (source, target, error))
                return None
        t, q = message.transform.translation, message.transform.rotation
        return quaternion_to_matrix((q.x, q.y, q.z, q.w)), np.array([t.x, t.y, t.z])

    def warn(self, text: str) -> None:
        """Each kind of warning (its text without the numbers) at most once per WARNING_PERIOD."""
        kind = NUMBERS.sub("#", text)
        now = rospy.get_time()
        last = self._last_warnings.get(kind)
        if last is None or abs(now - last) >= WARNING_PERIOD:
            self._last_warnings[kind] = now
            rospy.logwarn(text)

    # ---- output ----
    def on_timer(self, _event) -> None:
        with self.lock:
            estimate = self.localizer.update(rospy.Time.now().to_sec())
            if estimate is None or not estimate.publish:
                return
            odometry = self.odometry_message(estimate)
            if not np.all(np.isfinite(estimate.state)):
                rospy.logerr_throttle(
                    WARNING_PERIOD,
                    "Critical Error, NaNs were detected in the output state of "
                    "the filter. This was likely due to poorly conditioned process, noise, or "
                    "sensor covariances.",
                )
            if self.config.publish_tf:
                self.publish_transform(odometry)
            self.odometry_publisher.publish(odometry)
            if self.accel_publisher is not None:
                self.accel_publisher.publish(self.accel_message(estimate))

    def odometry_message(self, estimate: Estimate) -> Odometry:
        config, state, covariance = self.config, estimate.state, estimate.covariance
        message = Odometry()
        message.header.stamp = rospy.Time.from_sec(estimate.stamp)
        message.header.frame_id, message.child_frame_id = config.world_frame, config.base_link_frame_output
        pose, twist = message.pose.pose, message.twist.twist
        pose.position.x, pose.position.y, pose.position.z = state[0:3]
        q = pose.orientation
        q.x, q.y, q.z, q.w = rpy_to_quaternion(*state[3:6])
        twist.linear.x, twist.linear.y, twist.linear.z = state[6:9]
        twist.angular.x, twist.angular.y, twist.angular.z = state[9:12]
        message.pose.covariance = covariance[POSE_SLICE, POSE_SLICE].flatten().tolist()
        message.twist.covariance = covariance[TWIST_SLICE, TWIST_SLICE].flatten().tolist()
        return message

    def accel_message(self, estimate: Estimate) -> AccelWithCovarianceStamped:
        message = AccelWithCovarianceStamped()
        message.header.stamp = rospy.Time.from_sec(estimate.stamp)
        message.header.frame_id = self.config.base_link_frame_output
        linear, angular = message.accel.accel.linear, message.accel.accel.angular
        linear.x, linear.y, linear.z = estimate.state[ACCELERATION_SLICE]
        angular.x, angular.y, angular.z = estimate.angular_acceleration
        covariance = np.zeros((6, 6))
        covariance[:3, :3] = estimate.covariance[ACCELERATION_SLICE, ACCELERATION_SLICE]
        covariance[3:, 3:] = estimate.angular_acceleration_covariance
        message.accel.covariance = covariance.flatten().tolist()
        return message

    def publish_transform(self, odometry: Odometry) -> None:
        """world_frame -> base_link (inverted with invert_tf); with world_frame = map_frame, map -> odom from the
        odom -> base_link someone else publishes."""
        config = self.config
        stamp = odometry.header.stamp + rospy.Duration(config.transform_time_offset)
        p, q = odometry.pose.pose.position, odometry.pose.pose.orientation
        world_to_base = (quaternion_to_matrix((q.x, q.y, q.z, q.w)), np.array([p.x, p.y, p.z]))
        parent, child = odometry.header.frame_id, odometry.child_frame_id
        if config.invert_tf:
            self.tf_broadcaster.sendTransform(transform_message(inverse(world_to_base), stamp, child, parent))
        elif parent == config.odom_frame:
            self.tf_broadcaster.sendTransform(transform_message(world_to_base, stamp, parent, child))
        else:
            base_to_odom = self.lookup(config.base_link_frame, config.odom_frame, odometry.header.stamp.to_sec())
            if base_to_odom is None:
                self.warn("Could not obtain transform from %s->%s" % (config.odom_frame, config.base_link_frame))
                return
            map_to_odom = compose(world_to_base, base_to_odom)
            self.tf_broadcaster.sendTransform(
                transform_message(map_to_odom, stamp, config.map_frame, config.odom_frame)
            )


def main() -> None:
    rospy.init_node("ekf_navigation_node")  # upstream's default name; launch files give their own
    try:
        EkfNode()
        rospy.spin()
    except rospy.ROSInterruptException:
        pass
