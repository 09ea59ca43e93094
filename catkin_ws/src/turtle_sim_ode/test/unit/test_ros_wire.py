"""The packed messages are byte for byte what genpy serialises for the same field values."""
import io
import math
import random
import socket
import threading

import genpy
import numpy as np
import pytest
from geometry_msgs.msg import Quaternion, TransformStamped
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu, JointState, LaserScan
from tf2_msgs.msg import TFMessage
from workspace_testing.timing import assert_within, timed

from turtle_sim_ode.ros import wire as ros_wire

RNG = random.Random(8)
SEQ, SECS, NSECS = 42, 3, 999999999


def genpy_bytes(message):
    buffer = io.BytesIO()
    message.serialize(buffer)
    return buffer.getvalue()


def numbers(count):
    return tuple(RNG.uniform(-1e3, 1e3) for _ in range(count))


def with_header(message, frame_id):
    message.header.seq = SEQ
    message.header.stamp = genpy.Time(SECS, NSECS)
    message.header.frame_id = frame_id
    return message


def test_stamp_parts_round_to_the_nanosecond():
    assert ros_wire.stamp_parts(0.0) == (0, 0)
    assert ros_wire.stamp_parts(1.999999999) == (1, 999999999)
    assert ros_wire.stamp_parts(0.1 + 0.2) == (0, 300000000)
    assert ros_wire.stamp_parts(12345.0000000004) == (12345, 0)


def test_clock():
    assert ros_wire.ClockPacker().pack(SEQ, 7, 123) == genpy_bytes(Clock(genpy.Time(7, 123)))


@pytest.mark.parametrize("covariances", [True, False])
@pytest.mark.parametrize("frame_id, child_frame_id", [("odom", "base_footprint"), ("wörld", "")])
def test_odometry(covariances, frame_id, child_frame_id):
    pose_covariance, twist_covariance = (numbers(36), numbers(36)) if covariances else ((0.0,) * 36, (0.0,) * 36)
    position, orientation, linear, angular = numbers(3), numbers(4), numbers(3), numbers(3)
    odom = with_header(Odometry(), frame_id)
    odom.child_frame_id = child_frame_id
    pose = odom.pose.pose
    pose.position.x, pose.position.y, pose.position.z = position
    pose.orientation = Quaternion(*orientation)
    odom.pose.covariance = list(pose_covariance)
    twist = odom.twist.twist
    twist.linear.x, twist.linear.y, twist.linear.z = linear
    twist.angular.x, twist.angular.y, twist.angular.z = angular
    odom.twist.covariance = list(twist_covariance)
    if covariances:
        packer = ros_wire.OdometryPacker(frame_id, child_frame_id, pose_covariance, twist_covariance)
    else:
        packer = ros_wire.OdometryPacker(frame_id, child_frame_id)
    assert packer.pack(SEQ, SECS, NSECS, position, orientation, linear, angular) == genpy_bytes(odom)


def test_transform():
    translation, rotation = numbers(3), numbers(4)
    transform = with_header(TransformStamped(), "odom")
    transform.child_frame_id = "base_footprint"
    (
        transform.transform.translation.x,
        transform.transform.translation.y,
        transform.transform.translation.z,
    ) = translation
    transform.transform.rotation = Quaternion(*rotation)
    packed = ros_wire.TransformPacker("odom", "base_footprint").pack(SEQ, SECS, NSECS, translation, rotation)
    assert packed == genpy_bytes(TFMessage([transform]))


@pytest.mark.parametrize("names", [["wheel_left_joint", "wheel_right_joint"], ["only"], []])
def test_joint_state(names):
    positions, velocities = numbers(len(names)), numbers(len(names))
    joints = with_header(JointState(), "")
    joints.name, joints.position, joints.velocity = names, list(positions), list(velocities)
    packed = ros_wire.JointStatePacker(names).pack(SEQ, SECS, NSECS, positions, velocities)
    assert packed == genpy_bytes(joints)


@pytest.mark.parametrize("names", [["front_steering_joint", "front_wheel_joint"], []])
def test_joint_state_with_zero_efforts(names):
    positions, velocities = numbers(len(names)), numbers(len(names))
    joints = with_header(JointState(), "")
    joints.name, joints.position, joints.velocity = names, list(positions), list(velocities)
    joints.effort = [0.0] * len(names)
    packed = ros_wire.JointStatePacker(names, zero_efforts=True).pack(SEQ, SECS, NSECS, positions, velocities)
    assert packed == genpy_bytes(joints)


def test_imu():
    values = numbers(4), numbers(9), numbers(3), numbers(9), numbers(3), numbers(9)
    imu = with_header(Imu(), "imu_link")
    imu.orientation = Quaternion(*values[0])
    imu.orientation_covariance = list(values[1])
    imu.angular_velocity.x, imu.angular_velocity.y, imu.angular_velocity.z = values[2]
    imu.angular_velocity_covariance = list(values[3])
    imu.linear_acceleration.x, imu.linear_acceleration.y, imu.linear_acceleration.z = values[4]
    imu.linear_acceleration_covariance = list(values[5])
    assert ros_wire.ImuPacker("imu_link").pack(SEQ, SECS, NSECS, *values) == genpy_bytes(imu)


@pytest.mark.parametrize("beams", [360, 1])
def test_laser_scan(beams):
    geometry = numbers(7)
    ranges = [RNG.uniform(0.1, 3.5) for _ in range(beams)]
    ranges[0] = math.inf
    if beams > 2:
        ranges[1] = -math.inf
    scan = with_header(LaserScan(None, *geometry, ranges, []), "base_scan")
    packed = ros_wire.LaserScanPacker("base_scan", *geometry, beams).pack(SEQ, SECS, NSECS, ranges)
    assert packed == genpy_bytes(scan)


class _Connection:
    """What ros_wire.send uses of a rospy TCPROSTransport: a socket, done, close, stats."""

    def __init__(self, sock):
        self.socket = sock
        self.done = False
        self.stat_bytes = self.stat_num_msg = 0

    def close(self):
        self.done = True
        self.socket.close()
        self.socket = None


def _socket_pair(buffer_bytes):
    ours, theirs = socket.socketpair()
    ours.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, buffer_bytes)
    theirs.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, buffer_bytes)
    return ours, theirs


def test_send_reaches_readers_and_drops_a_stalled_or_gone_subscriber():
    reading_end, reader = _socket_pair(1 << 16)
    stalled_end, stalled_reader = _socket_pair(4096)  # never read: fills at once
    gone_end, gone = _socket_pair(4096)
    gone.close()
    reading, stalled, closed = _Connection(reading_end), _Connection(stalled_end), _Connection(gone_end)
    message = b"x" * 1000
    seconds, dropped = [], []
    for _ in range(40):
        sent, took = timed(lambda: ros_wire.send([reading, stalled, closed], message, 0.2))
        seconds.append(took)
        dropped += sent
        assert reader.recv(len(message), socket.MSG_WAITALL) == message  # the reader is served throughout
    assert dropped == [stalled] and stalled.done and closed.done and not reading.done
    held = max(seconds)  # held up once, for the timeout: the other 39 sends together took less
    assert_within(sum(seconds) - held, held, 1.0, "the 39 other sends")
    assert reading.stat_num_msg == 40 and reading.stat_bytes == 40 * len(message)
    for sock in (reader, stalled_reader, reading_end):
        sock.close()


def test_a_message_in_pieces_larger_than_the_socket_buffer_arrives_whole():
    """A camera's cloud goes out as pieces around a view of its buffer; the socket takes a few kB at a time."""
    sending_end, reader = _socket_pair(4096)
    cloud = np.arange(300000, dtype=np.uint32).view(np.uint8)
    pieces = (b"head", memoryview(cloud), b"", b"tail")
    received = bytearray()
    reading = threading.Thread(target=lambda: received.extend(reader.recv(1 << 24, socket.MSG_WAITALL)))
    reading.start()
    connection = _Connection(sending_end)
    assert ros_wire.send([connection], pieces, 5.0) == []
    sending_end.shutdown(socket.SHUT_WR)
    reading.join(5.0)
    assert bytes(received) == ros_wire.joined(pieces) == b"head" + cloud.tobytes() + b"tail"
    assert connection.stat_bytes == len(received) and connection.stat_num_msg == 1
    for sock in (reader, sending_end):
        sock.close()
