"""What /proc tells about a process and the machine, for the benchmark and the soak (scripts/bench_sim.py,
scripts/soak.py): CPU time, liveness, resident memory, threads and file descriptors by kind, stolen CPU ticks."""
from __future__ import annotations

import collections
import contextlib
import os
import time
from typing import Any, Dict, Tuple

from ros_run.processes import ToolError

STEADY_READS = 5  # threads and fds: the least of this many reads 50 ms apart (a service connection's thread and
STEADY_READ_GAP_S = 0.05  # socket live only as long as the call, and a sample must not catch one in passing)


def cpu_seconds(pid: int) -> float:
    """User + system CPU time of process ``pid``, all its threads."""
    with open("/proc/%d/stat" % pid) as stat:
        fields = stat.read().rsplit(")", 1)[1].split()  # from the state on: utime and stime are the 12th and 13th
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def cpu_ticks() -> Tuple[int, int]:
    """(all, stolen) CPU ticks of the machine so far (/proc/stat): on a virtual machine the host may take cores
    away for a while, and the figures of that stretch then come out low."""
    with open("/proc/stat") as stat:
        fields = [int(field) for field in stat.readline().split()[1:]]
    return sum(fields), fields[7] if len(fields) > 7 else 0


def process_alive(pid: int) -> bool:
    try:
        with open("/proc/%d/stat" % pid) as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] not in ("Z", "X")
    except OSError:
        return False


def rss_bytes(pid: int) -> int:
    with open("/proc/%d/status" % pid) as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    raise ToolError("no VmRSS for pid %d" % pid)


def fd_kind(target: str) -> str:
    """What an fd's /proc link points at: socket, eventpoll, pipe, anon (other anon_inode), dev or file."""
    if target.startswith("socket:"):
        return "socket"
    if target.startswith("pipe:"):
        return "pipe"
    if target == "anon_inode:[eventpoll]":
        return "eventpoll"
    if target.startswith("anon_inode:"):
        return "anon"
    return "dev" if target.startswith("/dev/") else "file"


def read_counts(pid: int) -> Tuple[int, Dict[str, int]]:
    """(threads, {fd kind: count}) of ``pid``."""
    threads = len(os.listdir("/proc/%d/task" % pid))
    kinds: Dict[str, int] = collections.Counter()
    fd_dir = "/proc/%d/fd" % pid
    for fd in os.listdir(fd_dir):
        with contextlib.suppress(OSError):  # closed meanwhile
            kinds[fd_kind(os.readlink(os.path.join(fd_dir, fd)))] += 1
    return threads, dict(kinds)


def steady_counts(pid: int) -> Dict[str, Any]:
    """Threads and fds as the least of STEADY_READS reads (a service connection's thread and socket live only while
    a call is served, and a sample must not catch one in passing), the fds by kind as in the read with the fewest,
    and the most threads and fds seen in the reads."""
    reads = []
    for index in range(STEADY_READS):
        if index:
            time.sleep(STEADY_READ_GAP_S)
        reads.append(read_counts(pid))
    fewest_fds = min(reads, key=lambda read: sum(read[1].values()))[1]
    return {
        "threads": min(read[0] for read in reads),
        "fds": sum(fewest_fds.values()),
        "fd_kinds": fewest_fds,
        "threads_max": max(read[0] for read in reads),
        "fds_max": max(sum(read[1].values()) for read in reads),
    }
