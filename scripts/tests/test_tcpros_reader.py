"""scripts/lib/ros_run/tcpros_reader.Reader closes exactly the streams it was given, whatever becomes of the list it
was given them in. The benchmark's probe once extended the list it had handed to one reader with another reader's
camera streams: closing the first shut the second's sockets under it, and the second failed with EBADF (a CI run's
test_bench_sim, "reading the topics failed: [Errno 9] Bad file descriptor")."""
import socket
import time

from conftest import LIB  # noqa: F401  (puts scripts/lib on the path)
from hypothesis import given, settings
from hypothesis import strategies as st
from ros_run.tcpros_reader import Reader


class PairStream:
    """A TopicStream's face (``sock``, ``read``) on one end of a socket pair; the test writes to the other end."""

    def __init__(self) -> None:
        self.sock, self.peer = socket.socketpair()
        self.received = 0

    def read(self) -> None:
        chunk = self.sock.recv(1 << 16)
        if not chunk:
            raise ConnectionError("peer closed")
        self.received += len(chunk)

    def close(self) -> None:
        self.sock.close()
        self.peer.close()


def wait_until(condition, timeout_s: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout_s
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.001)
    return True


@settings(max_examples=20, deadline=None)
@given(own=st.integers(1, 4), others=st.integers(1, 4), batch_s=st.sampled_from([0.0, 0.002]))
def test_closing_a_reader_leaves_streams_added_to_its_callers_list_alone(own, others, batch_s):
    first_streams = [PairStream() for _ in range(own)]
    second_streams = [PairStream() for _ in range(others)]
    given_list = list(first_streams)
    first = Reader(given_list, batch_s)
    second = Reader(second_streams)
    given_list += second_streams  # what the probe did
    try:
        first.close()
        assert all(stream.sock.fileno() == -1 for stream in first_streams)
        assert all(stream.sock.fileno() != -1 for stream in second_streams)
        for stream in second_streams:  # the second reader still reads every one of its streams
            stream.peer.sendall(b"x" * 100)
        assert wait_until(lambda: all(stream.received == 100 for stream in second_streams))
        assert second.error is None
    finally:
        second.close()
        for stream in first_streams + second_streams:
            stream.close()
