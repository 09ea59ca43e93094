"""RosFilter (ros_filter.cpp) without ROS: the sensors' data become measurements (pose, twist, acceleration; two_d_mode,
differential and relative modes, IMU mounting), wait in a queue ordered by time stamp, and are fused by the EKF at
each periodic update, which also predicts over a sensor time-out and says what to publish.

Transforms come from `lookup(target_frame, source_frame, stamp)`, which returns (R, t) or None (the node asks tf2).
"""
from __future__ import annotations

import heapq
import itertools
import math
from typing import Callable, Dict, List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from robot_localization.ekf import STATE_SIZE, VROLL, Ekf, Measurement, measured_indices
from robot_localization.params import Config, Sensor
from robot_localization.prepare import (
    ImuData,
    PoseData,
    Prepared,
    TwistData,
    force_two_d,
    pose_covariance,
    pose_transform,
    prepare_acceleration,
    prepare_twist,
    rotated_mask,
)
from robot_localization.rotations import (
    Transform,
    block_rotation,
    compose,
    identity,
    inverse_times,
    matrix_to_rpy,
    normalize_angle,
    rpy_to_matrix,
)

Lookup = Callable[[str, str, float], Optional[Transform]]
SET_POSE_VARIANCE = 1e-6  # setPoseCallback: the variance of what the pose message does not give


class Estimate(NamedTuple):
    """What a periodic update publishes: odometry/filtered (and its tf) unless `publish` is False (the stamp did
    not advance, upstream's corrected-data rule)."""

    stamp: float
    state: np.ndarray
    covariance: np.ndarray
    angular_acceleration: np.ndarray
    angular_acceleration_covariance: np.ndarray
    publish: bool


class Localizer:
    def __init__(self, config: Config, lookup: Lookup, now: float, warn: Callable[[str], None] = lambda _: None):
        self.config, self.lookup, self.warn = config, lookup, warn
        self.filter = Ekf()
        self.filter.process_noise = config.process_noise_covariance.copy()
        self.filter.dynamic_process_noise = config.dynamic_process_noise_covariance
        self.filter.sensor_timeout = config.sensor_timeout
        if config.initial_state is not None:
            self.filter.state = config.initial_state.copy()
        if config.initial_estimate_covariance is not None:
            self.filter.covariance = config.initial_estimate_covariance.copy()
        self.filter.last_measurement_time = now  # no huge first step
        self.enabled = not config.disabled_at_startup
        self.toggled_on = True
        self.use_sim_time = False
        self.queue: List[Tuple[float, int, Measurement]] = []
        self._order = itertools.count()
        self.previous: Dict[str, Tuple[Transform, np.ndarray]] = {}  # differential: last pose and covariance
        self.initial: Dict[str, Transform] = {}  # relative: first pose
        self.last_message_times: Dict[str, float] = {}
        self.last_set_pose_time = 0.0
        self.last_published_stamp = 0.0
        self.angular_acceleration = np.zeros(3)
        self.angular_acceleration_covariance = np.zeros((3, 3))
        self._last_rates, self._last_differentiation_time = np.zeros(3), now

    # ---- sensor callbacks (odometryCallback, poseCallback, twistCallback, imuCallback) ----
    def odometry(self, sensor: Sensor, pose: PoseData, twist: TwistData, child_frame_id: str) -> None:
        """nav_msgs/Odometry: the pose (in header.frame_id) and the twist (in child_frame_id) as two inputs."""
        if self._before_set_pose(sensor.name, pose.stamp):
            return
        if any(sensor.pose_update):
            source = child_frame_id if sensor.pose_use_child_frame else self.config.base_link_frame
            self._pose_input(sensor, pose, sensor.name + "_pose", self.config.world_frame, source, imu=False)
        if any(sensor.twist_update):
            self._twist_input(twist._replace(frame_id=child_frame_id), sensor.name + "_twist", sensor)

    def pose(self, sensor: Sensor, pose: PoseData) -> None:
        if not self._before_set_pose(sensor.name, pose.stamp):
            self._pose_input(sensor, pose, sensor.name, self.config.world_frame, self.config.base_link_frame, False)

    def twist(self, sensor: Sensor, twist: TwistData) -> None:
        if not self._before_set_pose(sensor.name, twist.stamp):
            self._twist_input(twist, sensor.name, sensor)

    def imu(self, sensor: Sensor, imu: ImuData) -> None:
        """sensor_msgs/Imu: orientation as a pose in base_link, angular velocity as a twist, acceleration; a part
        whose covariance starts with -1 is absent (sensor_msgs/Imu's rule)."""
        if self._before_set_pose(sensor.name, imu.stamp):
            return
        base_link = self.config.base_link_frame
        if any(sensor.pose_update) and not absent(imu.orientation_covariance):
            covariance = np.zeros((6, 6))
            covariance[3:, 3:] = np.reshape(imu.orientation_covariance, (3, 3))
            pose = PoseData(imu.stamp, imu.frame_id, (0.0, 0.0, 0.0), imu.orientation, covariance.flatten())
            self._pose_input(sensor, pose, sensor.name + "_pose", base_link, base_link, imu=True)
        if any(sensor.twist_update) and not absent(imu.angular_velocity_covariance):
            covariance = np.zeros((6, 6))
            covariance[3:, 3:] = np.reshape(imu.angular_velocity_covariance, (3, 3))
            twist = TwistData(imu.stamp, imu.frame_id, (0.0, 0.0, 0.0), imu.angular_velocity, covariance.flatten())
            self._twist_input(twist, sensor.name + "_twist", sensor)
        if any(sensor.acceleration_update) and not absent(imu.linear_acceleration_covariance):
            topic = sensor.name + "_acceleration"
            if self._accept(topic, imu.stamp):
                transform = self._lookup(base_link, imu.frame_id or base_link, imu.stamp)
                if transform is not None:
                    gravity = self.config.gravitational_acceleration
                    prepared = prepare_acceleration(
                        imu,
                        sensor.acceleration_update,
                        transform,
                        self.filter.state,
                        self.angular_acceleration,
                        gravity if sensor.remove_gravitational_acceleration else None,
                        sensor.relative,
                        self.config.two_d_mode,
                    )
                    self._enqueue(topic, prepared, sensor.thresholds[2], imu.stamp)
                self.last_message_times[topic] = imu.stamp

    def set_pose(self, pose: PoseData, now: float) -> None:
        """setPoseCallback: forget the sensors' history, ignore older messages, take the pose as the state."""
        self.initial.clear()
        self.previous.clear()
        self.queue.clear()
        self.last_set_pose_time = pose.stamp
        prepared = self._prepare_pose(
            pose,
            "set_pose",
            [True] * STATE_SIZE,
            self.config.world_frame,
            self.config.base_link_frame,
            False,
            False,
            False,
        )
        values = np.zeros(STATE_SIZE)
        covariance = np.eye(STATE_SIZE) * SET_POSE_VARIANCE
        if prepared is not None:
            values = prepared[0]
            covariance[:6, :6] = prepared[1][:6, :6]
            if self.config.two_d_mode:
                force_two_d(values, covariance, [True] * STATE_SIZE)
        self.filter.state, self.filter.covariance = values, covariance
        self.filter.last_measurement_time = now

    def reset(self) -> None:
        """RosFilter::reset (reset_on_time_jump): as if no measurement had come."""
        self.initial.clear()
        self.previous.clear()
        self.queue.clear()
        self.last_message_times.clear()
        self.last_set_pose_time = 0.0
        self.filter.reset()

    # ---- periodic update (periodicUpdate, integrateMeasurements, differentiateMeasurements) ----
    def update(self, now: float) -> Optional[Estimate]:
        if not self.enabled:
            return None
        if self.toggled_on:
            self.integrate(now)
            self.differentiate(now)
        else:
            self.queue.clear()
            if self.filter.initialized:
                self.filter.last_measurement_time = now
        if not self.filter.initialized:
            return None
        stamp = self.filter.last_measurement_time
        corrected = not self.config.permit_corrected_publication and self.last_published_stamp >= stamp
        self.last_published_stamp = stamp
        return Estimate(
            stamp,
            self.filter.state.copy(),
            self.filter.covariance.copy(),
            self.angular_acceleration.copy(),
            self.angular_acceleration_covariance.copy(),
            not corrected,
        )

    def integrate(self, now: float) -> None:
        """Fuse the queued measurements stamped up to now, oldest first; without any, predict up to now once the
        sensor time-out has passed (or always, with predict_to_current_time)."""
        predict = self.config.predict_to_current_time
        if self.queue:
            while self.queue and self.queue[0][0] <= now:
                self.filter.process_measurement(heapq.heappop(self.queue)[2])
        elif self.filter.initialized and now - self.filter.last_measurement_time >= self.filter.sensor_timeout:
            predict = True
        if self.filter.initialized and predict:
            self.filter.predict_to(now)

    def differentiate(self, now: float) -> None:
        """The angular acceleration from the change of the angular velocity since the last update."""
        dt = now - self._last_differentiation_time
        if not self.filter.initialized or dt <= 0.0:
            return
        rates = self.filter.state[VROLL : VROLL + 3].copy()
        self.angular_acceleration = (rates - self._last_rates) / dt
        block = self.filter.covariance[VROLL : VROLL + 3, VROLL : VROLL + 3]
        self.angular_acceleration_covariance = block * 2.0 / (dt * dt)
        self._last_rates, self._last_differentiation_time = rates, now

    # ---- preparation ----
    def _before_set_pose(self, name: str, stamp: float) -> bool:
        if stamp <= self.last_set_pose_time:
            self.warn(
                "The %s message has a timestamp equal to or before the last filter reset, this message will be "
                "ignored. This may indicate an empty or bad timestamp. (message time: %.9f)" % (name, stamp)
            )
            return True
        return False

    def _accept(self, topic: str, stamp: float) -> bool:
        """Only messages not older than the previous one of the same input (an older one resets the filter with
        reset_on_time_jump under simulated time)."""
        last = self.last_message_times.setdefault(topic, stamp)
        if stamp >= last:
            return True
        if self.config.reset_on_time_jump and self.use_sim_time:
            self.reset()
        else:
            self.warn(
                "The %s message has a timestamp before that of the previous message received, this message "
                "will be ignored. This may indicate a bad timestamp. (message time: %.9f)" % (topic, stamp)
            )
        return False

    def _pose_input(self, sensor: Sensor, pose: PoseData, topic: str, target: str, source: str, imu: bool) -> None:
        if not self._accept(topic, pose.stamp):
            return
        prepared = self._prepare_pose(
            pose, topic, sensor.pose_update, target, source, sensor.differential, sensor.relative, imu
        )
        # a differential pose becomes a twist: upstream gates it with the pose threshold all the same
        self._enqueue(topic, prepared, sensor.thresholds[0], pose.stamp)
        self.last_message_times[topic] = pose.stamp

    def _twist_input(self, twist: TwistData, topic: str, sensor: Sensor) -> None:
        if not self._accept(topic, twist.stamp):
            return
        self._enqueue(topic, self._prepare_twist(twist, sensor.twist_update), sensor.thresholds[1], twist.stamp)
        self.last_message_times[topic] = twist.stamp

    def _enqueue(self, topic: str, prepared: Optional[Prepared], threshold: float, stamp: float) -> None:
        """Queue a prepared measurement; one whose covariance is not finite would make the whole state NaN (as
        upstream's does): it is dropped with a warning."""
        if prepared is None:
            return
        measurement = Measurement(stamp, prepared[0], prepared[1], prepared[2], threshold, topic)
        indices = measured_indices(measurement)
        if not np.all(np.isfinite(measurement.covariance[np.ix_(indices, indices)])):
            self.warn("The %s message has a covariance that is not finite: ignored" % topic)
            return
        heapq.heappush(self.queue, (stamp, next(self._order), measurement))

    def _lookup(self, target: str, source: str, stamp: float) -> Optional[Transform]:
        """lookupTransformSafe: a frame to itself is the identity even without tf."""
        transform = self.lookup(target, source, stamp)
        return identity() if transform is None and target == source else transform

    def _prepare_twist(self, twist: TwistData, update: Sequence[bool]) -> Optional[Prepared]:
        base_link = self.config.base_link_frame
        transform = self._lookup(base_link, twist.frame_id or base_link, twist.stamp)
        if transform is None:
            return None
        return prepare_twist(twist, update, transform, self.filter.state, self.config.two_d_mode)

    def _prepare_pose(
        self,
        pose: PoseData,
        topic: str,
        update: Sequence[bool],
        target: str,
        source: str,
        differential: bool,
        relative: bool,
        imu: bool,
    ) -> Optional[Prepared]:
        """preparePose: into the target frame (an IMU's orientation: its mounting offsets removed, roll and pitch
        turned by its mounting yaw); in differential mode, the change since the last pose as a twist."""
        base_link = self.config.base_link_frame
        frame = target if differential and not imu else pose.frame_id
        target_transform = self._lookup(target, frame, pose.stamp)
        source_transform = self._lookup(source, base_link, pose.stamp) if source != base_link else None
        if target_transform is None:
            return None
        measured = pose_transform(pose)
        update = list(update)
        mounting_yaw = matrix_to_rpy(target_transform[0])[2]
        rotation = rpy_to_matrix(0.0, 0.0, mounting_yaw) if imu else target_transform[0]
        update[0:3] = rotated_mask(rotation, update[0:3])
        update[3:6] = rotated_mask(rotation, update[3:6])
        covariance = pose_covariance(pose)
        if source_transform is not None:
            source_rotation = block_rotation(source_transform[0])
            covariance = source_rotation.T @ covariance @ source_rotation
        rot6d = block_rotation(rotation)
        covariance_rotated = rot6d @ covariance @ rot6d.T
        if imu:
            offsets = matrix_to_rpy(target_transform[0])
            angles = [normalize_angle(a - o) for a, o in zip(matrix_to_rpy(measured[0]), offsets)]
            angles = rpy_to_matrix(0.0, 0.0, mounting_yaw) @ np.array(angles)
            measured = (rpy_to_matrix(*angles), measured[1])
            target_transform = identity()
        if differential:
            return self._pose_change(
                pose, topic, update, measured, covariance, covariance_rotated, target_transform[0], source
            )
        if source_transform is not None:
            measured = compose(measured, source_transform)
        if relative:
            measured = inverse_times(self.initial.setdefault(topic, measured), measured)
        measured = compose(target_transform, measured)
        values = np.zeros(STATE_SIZE)
        values[0:3] = measured[1]
        values[3:6] = matrix_to_rpy(measured[0])
        full_covariance = np.zeros((STATE_SIZE, STATE_SIZE))
        full_covariance[:6, :6] = covariance_rotated
        if self.config.two_d_mode:
            force_two_d(values, full_covariance, update)
        return values, full_covariance, update

    def _pose_change(
        self,
        pose: PoseData,
        topic: str,
        update: List[bool],
        measured: Transform,
        covariance: np.ndarray,
        covariance_rotated: np.ndarray,
        target_rotation: np.ndarray,
        source: str,
    ) -> Optional[Prepared]:
        """preparePose's differential branch: (previous^-1 current) / dt as a twist in `source`, its covariance
        (current + previous) dt; the first pose only starts the chain."""
        previous = self.previous.get(topic)
        self.previous[topic] = (measured, covariance)
        if previous is None:
            return None
        change = compose((target_rotation, np.zeros(3)), inverse_times(previous[0], measured))
        dt = pose.stamp - self.last_message_times[topic]
        rot6d = block_rotation(target_rotation)
        with np.errstate(divide="ignore", invalid="ignore"):  # dt 0: inf/nan, which correct() leaves out
            linear = change[1] / dt if dt else change[1] * math.inf
            angular = np.array(matrix_to_rpy(change[0])) / dt if dt else np.full(3, math.inf)
        twist_covariance = (covariance_rotated + rot6d @ previous[1] @ rot6d.T) * dt
        twist_update = [False] * STATE_SIZE
        twist_update[6:12] = update[0:6]
        twist = TwistData(pose.stamp, source, linear, angular, twist_covariance.flatten())
        return self._prepare_twist(twist, twist_update)


def absent(covariance: Sequence[float]) -> bool:
    return abs(covariance[0] + 1.0) < 1e-9
