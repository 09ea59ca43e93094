"""A light TCPROS subscriber for the benchmark: it connects to a topic's publishers as rospy or roscpp would (the
publisher sees an ordinary subscriber and writes it every message) but only splits the byte stream into messages,
without a Python callback per message, so that the measuring process stays light on a 2-core machine.

ROS 1 wire format: a connection header (4-byte length, then fields "key=value" each with a 4-byte length), answered
by the publisher's header, then each message as a 4-byte little-endian length and the serialized bytes.
"""
from __future__ import annotations

import selectors
import socket
import struct
import threading
import time
import xmlrpc.client
from typing import Callable, Dict, List, Optional

_LENGTH = struct.Struct("<I")
CONNECT_TIMEOUT_S = 10.0


def _header(fields: Dict[str, str]) -> bytes:
    items = [("%s=%s" % field).encode() for field in fields.items()]
    body = b"".join(_LENGTH.pack(len(item)) + item for item in items)
    return _LENGTH.pack(len(body)) + body


def _read_exactly(sock: socket.socket, count: int) -> bytes:
    data = b""
    while len(data) < count:
        chunk = sock.recv(count - len(data))
        if not chunk:
            raise ConnectionError("the publisher closed the connection during the handshake")
        data += chunk
    return data


class TopicStream:
    """One connection to one publisher of ``topic``: every message's arrival counted; the last one kept; each
    message handed to ``on_message(wall_time, payload)`` if given (for topics that need every message)."""

    def __init__(
        self,
        master_uri: str,
        caller_id: str,
        topic: str,
        on_message: Optional[Callable[[float, bytes], None]] = None,
        tcp_nodelay: bool = False,
        bulk: bool = False,
    ) -> None:
        """``tcp_nodelay`` asks the publisher to send each message at once (for arrival times): more packets, and
        more work for both ends, than letting TCP gather small messages as rospy subscribers do by default.
        ``bulk``: for messages of megabytes (a camera's): they are counted, not kept (``last`` stays None) nor
        copied, and the kernel sizes the socket's buffer itself (up to net.ipv4.tcp_rmem's maximum)."""
        self.topic = topic
        self._tcp_nodelay = tcp_nodelay
        self.count = 0
        self.last: Optional[bytes] = None
        self._on_message = on_message
        self._buffer = bytearray()
        self._bulk = bulk
        self._scratch = bytearray(1 << 20) if bulk else None
        self._length = bytearray()  # bulk: the length prefix read so far
        self._skip = 0  # bulk: payload bytes of the current message still to come
        self.sock = self._connect(master_uri, caller_id)

    def _connect(self, master_uri: str, caller_id: str) -> socket.socket:
        master = xmlrpc.client.ServerProxy(master_uri)
        _, _, (publishers, _, _) = master.getSystemState(caller_id)
        nodes = next((nodes for name, nodes in publishers if name == self.topic), [])
        if not nodes:
            raise ConnectionError("%s has no publisher" % self.topic)
        code, message, node_uri = master.lookupNode(caller_id, nodes[0])
        if code != 1:
            raise ConnectionError("%s: %s" % (nodes[0], message))
        code, message, protocol = xmlrpc.client.ServerProxy(node_uri).requestTopic(caller_id, self.topic, [["TCPROS"]])
        if code != 1:
            raise ConnectionError("%s refused %s: %s" % (nodes[0], self.topic, message))
        _, host, port = protocol
        sock = socket.create_connection((host, port), timeout=CONNECT_TIMEOUT_S)
        # md5sum and type "*": any type (rospy.AnyMsg asks the same way).
        fields = {
            "callerid": caller_id,
            "topic": self.topic,
            "md5sum": "*",
            "type": "*",
            "tcp_nodelay": str(int(self._tcp_nodelay)),
        }
        sock.sendall(_header(fields))
        answer = _read_exactly(sock, _LENGTH.unpack(_read_exactly(sock, 4))[0])
        if b"error=" in answer:
            raise ConnectionError("%s: %s" % (self.topic, answer))
        sock.settimeout(None)
        if not self._bulk:
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1 << 20)
        return sock

    def read(self) -> None:
        """Take what has arrived (call when the socket is readable)."""
        if self._bulk:
            self._count_bulk()
            return
        chunk = self.sock.recv(1 << 20)
        if not chunk:
            raise ConnectionError("%s: the publisher closed the connection" % self.topic)
        now = time.monotonic()
        data = self._buffer  # appended to in place: a message of megabytes (a camera's) arrives in many chunks
        data += chunk
        offset, end = 0, len(data)
        while end - offset >= 4:
            (size,) = _LENGTH.unpack_from(data, offset)
            if end - offset - 4 < size:
                break
            payload = bytes(data[offset + 4 : offset + 4 + size])
            offset += 4 + size
            self.count += 1
            self.last = payload
            if self._on_message is not None:
                self._on_message(now, payload)
        del data[:offset]

    def _count_bulk(self) -> None:
        """Read into one reused buffer, following the length prefixes and counting the messages they close."""
        size = self.sock.recv_into(self._scratch)
        if not size:
            raise ConnectionError("%s: the publisher closed the connection" % self.topic)
        offset = 0
        while offset < size:
            if self._skip:
                taken = min(self._skip, size - offset)
                self._skip -= taken
                offset += taken
                if not self._skip:
                    self.count += 1
                continue
            taken = min(4 - len(self._length), size - offset)
            self._length += self._scratch[offset : offset + taken]
            offset += taken
            if len(self._length) == 4:
                (self._skip,) = _LENGTH.unpack(self._length)
                self._length = bytearray()
                if not self._skip:
                    self.count += 1


class Reader:
    """Reads ``TopicStream``s in a thread of its own until ``close``. With ``batch_s`` it waits that long after each
    read: a sender whose subscriber is asleep in select() pays for waking it on every message (a cross-CPU wake-up
    on a VM), and a reader that drains its sockets a few hundred times a second spares it most of them."""

    def __init__(self, streams: List[TopicStream], batch_s: float = 0.0) -> None:
        self.streams = list(streams)  # its own: ``close`` shuts exactly these, whatever becomes of the caller's list
        self.error: Optional[BaseException] = None
        self._batch_s = batch_s
        self._selector = selectors.DefaultSelector()
        for stream in streams:
            self._selector.register(stream.sock, selectors.EVENT_READ, stream)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        try:
            while not self._stop.is_set():
                for key, _ in self._selector.select(0.1):
                    key.data.read()
                if self._batch_s:
                    time.sleep(self._batch_s)
        except (OSError, ConnectionError) as error:
            if not self._stop.is_set():  # not a socket ``close`` shut under a read that outlived the join below
                self.error = error

    def close(self) -> None:
        self._stop.set()
        self._thread.join(30.0)  # a bulk read on a loaded machine may take seconds
        for stream in self.streams:
            stream.sock.close()
        self._selector.close()


def clock_stamp(payload: bytes) -> float:
    """rosgraph_msgs/Clock: seconds."""
    secs, nsecs = struct.unpack("<2I", payload)
    return secs + nsecs * 1e-9
