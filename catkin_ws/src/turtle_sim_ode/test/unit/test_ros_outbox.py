"""ros.wire's Outbox (issue #33): the stepping thread's messages are held and written one write per connection; every
subscriber still gets every message whole, in order, with the seq its topic gave it; another thread's message goes
out after what was held."""
from __future__ import annotations

import socket
import struct
import threading

from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.ros import wire as ros_wire

CLOCK = ros_wire.ClockPacker()


class _CountingSocket:
    """A socket whose writes are counted."""

    def __init__(self, sock: socket.socket) -> None:
        self.sock = sock
        self.writes = 0

    def send(self, data, flags=0):
        self.writes += 1
        return self.sock.send(data, flags)

    def sendmsg(self, buffers, ancdata=(), flags=0):
        self.writes += 1
        return self.sock.sendmsg(buffers, ancdata, flags)


class _Connection:
    """What ros.wire uses of a rospy TCPROSTransport."""

    def __init__(self, sock: socket.socket) -> None:
        self.socket = _CountingSocket(sock)
        self.done = False
        self.stat_bytes = self.stat_num_msg = 0
        self.endpoint_id = "reader"

    def close(self) -> None:
        self.done = True


class _Topic:
    """What ros.wire uses of rospy's topic implementation."""

    def __init__(self, name: str, connections) -> None:
        self.resolved_name = name
        self.connections = connections
        self.publock = threading.Lock()
        self.seq = 0
        self.message_data_sent = 0


class _Publisher:
    def __init__(self, impl: _Topic) -> None:
        self.impl = impl


def publisher(impl: _Topic) -> ros_wire.PackedPublisher:
    packed = ros_wire.PackedPublisher.__new__(ros_wire.PackedPublisher)
    packed._pub = _Publisher(impl)
    return packed


def stamped(seq: int, secs: int, nsecs: int) -> bytes:
    """A message whose bytes hold its seq (a Clock carries none)."""
    return struct.pack("<3I", seq, secs, nsecs)


def received(reader: socket.socket):
    """The (seq, secs, nsecs) of every whole message waiting in ``reader``."""
    reader.setblocking(False)
    data = b""
    try:
        while True:
            chunk = reader.recv(1 << 16)
            if not chunk:
                break
            data += chunk
    except BlockingIOError:
        pass
    messages = []
    while data:
        (length,) = struct.unpack_from("<I", data)
        assert length == 12 and len(data) >= 4 + length, "a message was cut"
        messages.append(struct.unpack_from("<3I", data, 4))
        data = data[4 + length :]
    return messages


def pair():
    ours, theirs = socket.socketpair()
    return _Connection(ours), theirs


def test_held_messages_go_out_in_one_write_per_connection_in_order() -> None:
    outbox = ros_wire.Outbox(period_s=10.0)
    (a1, reader_a1), (a2, reader_a2), (b, reader_b) = pair(), pair(), pair()
    topic_a, topic_b = _Topic("/a", [a1, a2]), _Topic("/b", [b])
    original, ros_wire.OUTBOX = ros_wire.OUTBOX, outbox
    try:
        outbox.hold()
        for index in range(5):
            publisher(topic_a).publish(stamped, index, 0)
            if index < 3:
                publisher(topic_b).publish(stamped, 100 + index, 0)
        outbox.flush_due()  # 10 s have not passed
        assert received(reader_a1) == [] and received(reader_b) == []
        outbox.flush()
        outbox.hold(False)
    finally:
        ros_wire.OUTBOX = original
    expected_a = [(seq, index, 0) for seq, index in zip(range(1, 6), range(5))]
    assert received(reader_a1) == received(reader_a2) == expected_a
    assert received(reader_b) == [(1, 100, 0), (2, 101, 0), (3, 102, 0)]
    assert (a1.socket.writes, a2.socket.writes, b.socket.writes) == (1, 1, 1)
    assert (a1.stat_num_msg, b.stat_num_msg) == (5, 3) and a1.stat_bytes == 5 * 16
    assert topic_a.message_data_sent == 5 * 16 and topic_a.seq == 5


def test_another_threads_message_follows_the_held_ones() -> None:
    outbox = ros_wire.Outbox(period_s=10.0)
    connection, reader = pair()
    topic = _Topic("/clock", [connection])
    original, ros_wire.OUTBOX = ros_wire.OUTBOX, outbox
    try:
        outbox.hold()
        publisher(topic).publish(stamped, 1, 0)
        publisher(topic).publish(stamped, 2, 0)
        other = threading.Thread(target=lambda: publisher(topic).publish(stamped, 3, 0))
        other.start()
        other.join(5.0)
        outbox.hold(False)
    finally:
        ros_wire.OUTBOX = original
    assert received(reader) == [(1, 1, 0), (2, 2, 0), (3, 3, 0)]


def test_unheld_and_zero_period_write_each_message_at_once() -> None:
    connection, reader = pair()
    topic = _Topic("/clock", [connection])
    publisher(topic).publish(CLOCK.pack, 7, 8)  # nobody holds: written at once
    assert connection.socket.writes == 1 and connection.stat_num_msg == 1
    reader.setblocking(False)
    assert reader.recv(64) == struct.pack("<I", 8) + struct.pack("<2I", 7, 8)


@settings(max_examples=60, deadline=None)
@given(
    steps=st.lists(st.tuples(st.lists(st.integers(0, 2), max_size=4), st.booleans()), min_size=1, max_size=40),
    max_bytes=st.sampled_from([16, 64, 1 << 20]),
)
def test_generated_publishes_and_flushes_arrive_whole_and_in_order(steps, max_bytes) -> None:
    """Steps of publishes on three topics (one with two subscribers), flushed when due at random, and whenever more
    than ``max_bytes`` is held: each subscriber reads its topic's messages, all of them, in order."""
    outbox = ros_wire.Outbox(period_s=10.0, max_bytes=max_bytes)
    pairs = [pair() for _ in range(4)]
    topics = [_Topic("/t0", [pairs[0][0], pairs[1][0]]), _Topic("/t1", [pairs[2][0]]), _Topic("/t2", [pairs[3][0]])]
    sent = [[], [], []]
    original, ros_wire.OUTBOX = ros_wire.OUTBOX, outbox
    try:
        outbox.hold()
        for publishes, flush in steps:
            for topic in publishes:
                value = len(sent[topic])
                publisher(topics[topic]).publish(stamped, value, topic)
                sent[topic].append((value + 1, value, topic))
            if flush:
                outbox.flush()
        outbox.hold(False)
    finally:
        ros_wire.OUTBOX = original
    readers = [received(reader) for _, reader in pairs]
    assert readers == [sent[0], sent[0], sent[1], sent[2]]
    for connection, reader in pairs:
        reader.close()
        connection.socket.sock.close()
