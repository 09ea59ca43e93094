"""The messages the simulator publishes at step rates, packed straight into ROS 1's wire format and written
synchronously.

Why (issue #8, measured on the 2-core dev machine): a genpy Odometry costs ~10 us to build and ~15 us to serialise,
and a rospy publisher with a queue (queue_size=N) hands every message to a writer thread with time.sleep(0), a
thread switch of 100-150 us. With one TurtleBot that was ~360 messages and ~50 ms of wall time per simulated second.
One struct.pack of the whole message, written synchronously, costs a few us besides the socket write. The bytes are
those genpy would write (test_ros_wire.py compares them).

Written by this module straight to each subscriber's socket, not by rospy's Publisher.publish (whose argument checks,
buffer juggling and write_data made an Odometry cost 11-19 us against 9-10 us, socket write included, in two runs on
the dev machine), with a send timeout: a subscriber process that stops reading altogether (stopped, not merely slow:
rospy and roscpp read their sockets in threads of their own) would otherwise block the simulator for good once the
kernel's socket buffers (megabytes) are full. One that takes nothing for STALLED_SUBSCRIBER_TIMEOUT_S is dropped with
a warning; it may subscribe again.

Held, in a thread that asks for it (the node's stepping loop, issue #33): that thread's step-rate messages wait in
``OUTBOX`` and go out as one write per connection once they are ``Outbox.period_s`` of wall time old, or sooner when
the thread flushes before it waits. Every write to a loopback socket whose reader sleeps in select() wakes it, and on
the 2-core dev machine that wake-up cost 6 to 47 us a message against 2.5 us for the write itself; with one write
per connection every millisecond or so an unthrottled simulator wakes its subscribers a few hundred times a second,
not once a message. Each subscriber still gets every message whole and in order; what changes is only that a
message may reach it up to ``period_s`` of wall time later, while the simulation runs faster than real time.
"""
from __future__ import annotations

import select
import socket
import struct
import threading
import time
import warnings
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import rospy

# A packed message: its bytes, or its pieces in order (bytes and memoryviews of bytes), which are written with one
# sendmsg() each: a camera's megabytes are then copied once, by the kernel, not joined first (issue #15).
Packed = Union[bytes, Sequence[Union[bytes, memoryview]]]
Vec3 = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]  # x, y, z, w as in geometry_msgs

_HEADER = "3I%ds"  # seq, stamp secs, stamp nsecs, then frame_id as a length-prefixed string
_LENGTH = struct.Struct("<I")  # TCPROS frames each message with its length
# Wall seconds a subscriber's socket may stay full before the subscriber is dropped (see the module's docstring).
STALLED_SUBSCRIBER_TIMEOUT_S = 2.0


def _string(text: str) -> bytes:
    data = text.encode("utf-8")
    return struct.pack("<I", len(data)) + data


def _float64s(values: Sequence[float]) -> bytes:
    """A fixed-size float64[N] (covariances): no length prefix."""
    return struct.pack("<%dd" % len(values), *values)


def pieces(packed: Packed) -> List[memoryview]:
    """A packed message as byte views (no copy)."""
    if isinstance(packed, (bytes, bytearray, memoryview)):
        packed = (packed,)
    return [memoryview(piece).cast("B") for piece in packed]


def size_of(packed: Packed) -> int:
    return len(packed) if isinstance(packed, bytes) else sum(len(view) for view in pieces(packed))


def joined(packed: Packed) -> bytes:
    """A packed message's bytes (a copy if it is in pieces)."""
    return packed if isinstance(packed, bytes) else b"".join(pieces(packed))


def stamp_parts(seconds: float) -> Tuple[int, int]:
    """(secs, nsecs) of a sim time, rounded to the nanosecond as plugin_topics.sim_stamp does."""
    nanoseconds = int(round(seconds * 1e9))
    return nanoseconds // 1000000000, nanoseconds % 1000000000


class PackedPublisher:
    """A rospy publisher of packed messages (bytes in the wire format of ``data_class``), written synchronously
    (see the module's docstring)."""

    def __init__(self, topic: str, data_class: type) -> None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SyntaxWarning)  # rospy warns of queue_size=None, meant here
            self._pub = rospy.Publisher(topic, data_class, queue_size=None)

    def get_num_connections(self) -> int:
        return self._pub.get_num_connections()

    def heard(self) -> bool:
        return heard(self._pub)

    def on_subscribers_changed(self, changed: Callable[[], None]) -> None:
        """Call ``changed()`` (from a rospy thread) whenever a subscriber comes or goes."""
        listener = rospy.SubscribeListener()
        listener.peer_subscribe = lambda *_: changed()  # type: ignore[assignment]
        listener.peer_unsubscribe = lambda *_: changed()  # type: ignore[assignment]
        self._pub.impl.add_subscriber_listener(listener)

    def publish(self, pack: Callable[..., Packed], *fields: Any) -> None:
        """Publish the message ``pack(seq, *fields)`` if anyone listens (nothing is packed otherwise); seq is the
        header seq rospy gives the topic's next message, as it would to a genpy message."""
        impl = self._pub.impl
        lock = impl.publock if impl is not None else None  # None once rospy has closed the topic (shutdown)
        if lock is None or not impl.connections:
            return
        outbox = OUTBOX
        if outbox.holds():
            with lock:  # rospy's own, for seq
                impl.seq += 1
                packed = pack(impl.seq, *fields)
            if isinstance(packed, bytes):  # a step-rate message: held (see the module's docstring)
                outbox.add(impl, _LENGTH.pack(len(packed)) + packed)
                return
            outbox.flush()  # a large message goes at once, after what its subscribers were due before it
        else:
            if outbox.pending:  # the holding thread's messages go first
                outbox.flush()
            with lock:
                impl.seq += 1
                packed = pack(impl.seq, *fields)
        data: Packed
        if isinstance(packed, bytes):  # a step-rate message: one small copy costs less than views of it
            data = _LENGTH.pack(len(packed)) + packed
        else:
            payload = pieces(packed)
            data = [memoryview(_LENGTH.pack(sum(len(piece) for piece in payload)))] + payload
        with lock:  # one message at a time on the sockets, as rospy's publish does
            stalled = send(impl.connections, data, STALLED_SUBSCRIBER_TIMEOUT_S)
            impl.message_data_sent += size_of(data)
        _warn_stalled(impl.resolved_name, stalled)

    def unregister(self) -> None:
        release(self._pub)


def heard(publisher: rospy.Publisher) -> bool:
    """Whether ``publisher`` has a subscriber: get_num_connections() without its lock (a step-rate check)."""
    impl = publisher.impl
    return impl is not None and bool(impl.connections)


def _warn_stalled(topic: str, stalled: Sequence[Any]) -> None:
    for connection in stalled:
        rospy.logwarn(
            "%s: subscriber %s took no message for %.0f s: dropped (it may subscribe again)",
            topic,
            connection.endpoint_id,
            STALLED_SUBSCRIBER_TIMEOUT_S,
        )


class Outbox:
    """The step-rate messages of the thread that holds them, per connection, until they are written together (see
    the module's docstring)."""

    def __init__(self, period_s: float = 0.001, max_bytes: int = 1 << 20) -> None:
        self.period_s = period_s
        self.max_bytes = max_bytes  # written at once past this many bytes held
        self.pending: Dict[Any, Tuple[Any, List[bytes]]] = {}  # connection: (rospy's topic impl, framed messages)
        self._holder: Optional[int] = None
        self._oldest = 0.0  # time.monotonic() of the oldest message held
        self._bytes = 0
        self._lock = threading.Lock()

    def hold(self, holding: bool = True) -> None:
        """The calling thread's step-rate messages are held from now on (``holding``), or written at once again."""
        self.flush()
        self._holder = threading.get_ident() if holding else None

    def holds(self) -> bool:
        return self._holder == threading.get_ident()

    def add(self, impl: Any, data: bytes) -> None:
        with self._lock:
            if not self.pending:
                self._oldest = time.monotonic()
            for connection in impl.connections:
                held = self.pending.get(connection)
                if held is None:
                    self.pending[connection] = (impl, [data])
                else:
                    held[1].append(data)
            impl.message_data_sent += len(data)
            self._bytes += len(data)
        if self._bytes >= self.max_bytes:
            self.flush()

    def flush_due(self) -> None:
        """Write what is held if the oldest of it is ``period_s`` old."""
        if self.pending and time.monotonic() - self._oldest >= self.period_s:
            self.flush()

    def flush(self) -> None:
        """Write every connection's held messages, one write each."""
        if not self.pending:
            return
        with self._lock:
            pending, self.pending, self._bytes = self.pending, {}, 0
            for connection, (impl, messages) in pending.items():
                with impl.publock:
                    stalled = send([connection], b"".join(messages), STALLED_SUBSCRIBER_TIMEOUT_S, len(messages))
                _warn_stalled(impl.resolved_name, stalled)


OUTBOX = Outbox()


def send(connections: Sequence[Any], data: Packed, timeout: float, messages: int = 1) -> List[Any]:
    """Write ``data`` (``messages`` framed messages) to each rospy TCPROS connection; one that fails is closed (rospy
    then forgets it). Returns those that timed out: their subscriber took nothing for ``timeout`` wall seconds."""
    stalled = []
    size = size_of(data)
    for connection in connections:
        if connection.done:
            continue
        sock = getattr(connection, "socket", None)
        if sock is None:  # not a plain TCPROS connection (another publisher of the topic gave it a queue)
            connection.write_data(joined(data))
            continue
        try:
            _send_all(sock, data, timeout)
        except socket.timeout:
            stalled.append(connection)
            connection.close()  # part of a message may have gone: the stream cannot be resumed
        except OSError:  # the subscriber went away (EPIPE, ECONNRESET)
            connection.close()
        else:
            connection.stat_bytes += size
            connection.stat_num_msg += messages
    return stalled


def _send_all(sock: socket.socket, data: Packed, timeout: float) -> None:
    """sock.sendall of ``data`` with a timeout (socket.timeout), leaving the socket blocking as rospy has it. One
    non-blocking send() (sendmsg() of pieces) as a rule: a socket with a timeout of its own would cost a poll() before
    every send."""
    if isinstance(data, bytes):
        try:
            sent = sock.send(data, socket.MSG_DONTWAIT)
        except BlockingIOError:
            sent = 0
        if sent == len(data):
            return
        views = [memoryview(data)[sent:]]
    else:
        views = pieces(data)
    deadline = None
    while views:
        try:
            sent = sock.sendmsg(views, (), socket.MSG_DONTWAIT)
        except BlockingIOError:
            sent = 0
        while views and sent >= len(views[0]):  # drop what went, whole pieces first
            sent -= len(views[0])
            views = views[1:]
        if not views:
            return
        views = [views[0][sent:]] + views[1:]
        if deadline is None:
            deadline = time.monotonic() + timeout
        remaining = deadline - time.monotonic()
        if remaining <= 0 or not select.select([], [sock], [], remaining)[1]:
            raise socket.timeout("no room in the socket for %.1f s" % timeout)


def release(handle: Any) -> None:
    """Unregister a rospy Publisher or Subscriber (or a PackedPublisher). When it was its topic's last user, also
    close the topic's epoll fd: rospy leaves that to the garbage collector (a reference cycle), and a simulator that
    spawns and deletes models would otherwise pile up fds between collections (ros/ros_comm#2373)."""
    if isinstance(handle, PackedPublisher):
        handle.unregister()
        return
    impl = handle.impl
    handle.unregister()
    poller = getattr(getattr(impl, "connection_poll", None), "poller", None)
    if impl is not None and impl.closed and hasattr(poller, "close"):
        poller.close()


class ClockPacker:
    """rosgraph_msgs/Clock (no header: the seq is ignored)."""

    _struct = struct.Struct("<2I")

    def pack(self, _seq: int, secs: int, nsecs: int) -> bytes:
        return self._struct.pack(secs, nsecs)


class OdometryPacker:
    """nav_msgs/Odometry with fixed frames and covariances."""

    def __init__(
        self,
        frame_id: str,
        child_frame_id: str,
        pose_covariance: Sequence[float] = (0.0,) * 36,
        twist_covariance: Sequence[float] = (0.0,) * 36,
    ) -> None:
        frames = _string(frame_id) + _string(child_frame_id)
        self._frames = frames
        self._pose_covariance = _float64s(pose_covariance)
        self._twist_covariance = _float64s(twist_covariance)
        self._struct = struct.Struct("<" + _HEADER % len(frames) + "7d288s6d288s")

    def pack(
        self, seq: int, secs: int, nsecs: int, position: Vec3, orientation: Quat, linear: Vec3, angular: Vec3
    ) -> bytes:
        return self._struct.pack(
            seq,
            secs,
            nsecs,
            self._frames,
            *position,
            *orientation,
            self._pose_covariance,
            *linear,
            *angular,
            self._twist_covariance,
        )


class TransformPacker:
    """tf2_msgs/TFMessage holding one geometry_msgs/TransformStamped between fixed frames."""

    def __init__(self, frame_id: str, child_frame_id: str) -> None:
        frames = _string(frame_id) + _string(child_frame_id)
        self._frames = frames
        # The transforms array's length (1) comes first.
        self._struct = struct.Struct("<I" + _HEADER % len(frames) + "7d")

    def pack(self, seq: int, secs: int, nsecs: int, translation: Vec3, rotation: Quat) -> bytes:
        return self._struct.pack(1, seq, secs, nsecs, self._frames, *translation, *rotation)


class JointStatePacker:
    """sensor_msgs/JointState of fixed joint names and frame_id: positions and velocities; no efforts, or a zero
    effort a joint with ``zero_efforts`` (as a Gazebo plugin reports a motor-driven joint's GetForce)."""

    def __init__(self, names: Sequence[str], frame_id: str = "", zero_efforts: bool = False) -> None:
        count = len(names)
        fixed = _string(frame_id) + struct.pack("<I", count) + b"".join(_string(name) for name in names)
        efforts = count if zero_efforts else 0
        self._fixed = fixed
        self._count = count
        self._efforts = struct.pack("<I%dd" % efforts, efforts, *([0.0] * efforts))
        self._struct = struct.Struct("<" + _HEADER % len(fixed) + "I%ddI%dd%ds" % (count, count, len(self._efforts)))

    def pack(self, seq: int, secs: int, nsecs: int, positions: Sequence[float], velocities: Sequence[float]) -> bytes:
        count = self._count
        return self._struct.pack(seq, secs, nsecs, self._fixed, count, *positions, count, *velocities, self._efforts)


class ImuPacker:
    """sensor_msgs/Imu in a fixed frame."""

    def __init__(self, frame_id: str) -> None:
        frame = _string(frame_id)
        self._frame = frame
        self._struct = struct.Struct("<" + _HEADER % len(frame) + "4d9d3d9d3d9d")

    def pack(
        self,
        seq: int,
        secs: int,
        nsecs: int,
        orientation: Quat,
        orientation_covariance: Sequence[float],
        angular_velocity: Vec3,
        angular_velocity_covariance: Sequence[float],
        linear_acceleration: Vec3,
        linear_acceleration_covariance: Sequence[float],
    ) -> bytes:
        return self._struct.pack(
            seq,
            secs,
            nsecs,
            self._frame,
            *orientation,
            *orientation_covariance,
            *angular_velocity,
            *angular_velocity_covariance,
            *linear_acceleration,
            *linear_acceleration_covariance,
        )


class LaserScanPacker:
    """sensor_msgs/LaserScan of a fixed frame, geometry and beam count; no intensities."""

    def __init__(
        self,
        frame_id: str,
        angle_min: float,
        angle_max: float,
        angle_increment: float,
        time_increment: float,
        scan_time: float,
        range_min: float,
        range_max: float,
        beams: int,
    ) -> None:
        fixed = _string(frame_id)
        self._frame = fixed
        self._geometry = struct.pack(
            "<7f", angle_min, angle_max, angle_increment, time_increment, scan_time, range_min, range_max
        )
        self._beams = beams
        self._struct = struct.Struct("<" + _HEADER % len(fixed) + "28sI%dfI" % beams)

    def pack(self, seq: int, secs: int, nsecs: int, ranges: Sequence[float]) -> bytes:
        return self._struct.pack(seq, secs, nsecs, self._frame, self._geometry, self._beams, *ranges, 0)
