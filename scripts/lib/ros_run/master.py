"""The ROS side shared by the benchmark and the soak (scripts/bench_sim.py, scripts/soak.py): a master of the tool's own
on a free loopback port with the launches made on it, waiting for a condition, a node's process id, and whether a
service is offered."""
from __future__ import annotations

import contextlib
import os
import subprocess
import time
import xmlrpc.client
from typing import Iterator, List, Sequence

from ros_run.processes import Processes, ToolError, free_port


class Master:
    """A roscore of our own on a free port; ``ros_env`` points ROS processes at it, ``close`` stops it and what was
    launched on it. Its logs are ``<name>-roscore.log`` and ``<name>-launch.log`` in the log directory (without
    ``<name>-`` when ``name`` is empty); ``caller_id`` is what the tool calls itself towards the master."""

    def __init__(self, processes: Processes, name: str, caller_id: str, timeout: float) -> None:
        self.processes = processes
        self.name = name
        self.started: List[subprocess.Popen] = []
        port = free_port()
        self.uri = "http://127.0.0.1:%d" % port
        self.ros_env = {
            "ROS_MASTER_URI": self.uri,
            "ROS_IP": "127.0.0.1",
            "ROS_HOSTNAME": "127.0.0.1",
            "ROS_LOG_DIR": processes.log_dir,
        }
        roscore = self._start(["roscore", "-p", str(port)], "roscore")
        deadline = time.monotonic() + timeout
        while True:
            with contextlib.suppress(OSError):
                xmlrpc.client.ServerProxy(self.uri).getPid(caller_id)
                return
            if roscore.poll() is not None or time.monotonic() > deadline:
                self.close()
                raise ToolError("roscore did not start:\n" + self.log_tail("roscore"))
            time.sleep(0.1)

    def log_name(self, log: str) -> str:
        return "%s-%s.log" % (self.name, log) if self.name else log + ".log"

    def log_tail(self, log: str) -> str:
        """The last lines of the log of ``log`` ("roscore" or "launch")."""
        return self.processes.log_tail(self.log_name(log))

    def _start(self, command: List[str], log: str) -> subprocess.Popen:
        process = self.processes.start(command, dict(os.environ, **self.ros_env), self.log_name(log))
        self.started.append(process)
        return process

    def launch(self, launch_file: str, arguments: Sequence[str]) -> subprocess.Popen:
        return self._start(["roslaunch", "turtle_sim_ode", launch_file] + list(arguments), "launch")

    def close(self) -> None:
        for process in reversed(self.started):
            self.processes.stop(process)

    def failure(self, launch: subprocess.Popen, error: ToolError) -> ToolError:
        """``error`` (of the same class) with the launch's exit status and the tail of its log."""
        status = "running" if launch.poll() is None else "exited %s" % launch.returncode
        return type(error)("%s\nroslaunch (%s):\n%s" % (error, status, self.log_tail("launch")))


@contextlib.contextmanager
def master(processes: Processes, name: str, caller_id: str, timeout: float) -> Iterator[Master]:
    """A fresh master; it and every launch made on it are stopped on leaving."""
    ros = Master(processes, name, caller_id, timeout)
    try:
        yield ros
    finally:
        ros.close()


def node_pid(name: str, caller_id: str) -> int:
    """Process id of the ROS node ``name``, asked through its XML-RPC API."""
    import rosgraph

    code, message, pid = xmlrpc.client.ServerProxy(rosgraph.Master(caller_id).lookupNode(name)).getPid(caller_id)
    if code != 1:
        raise ToolError("%s did not tell its pid: %s" % (name, message))
    return int(pid)


def service_offered(service: str, caller_id: str) -> bool:
    """Whether the master of ROS_MASTER_URI knows ``service`` (False while there is no master to ask)."""
    import rosgraph

    try:
        rosgraph.Master(caller_id).lookupService(service)
        return True
    except (OSError, rosgraph.MasterException):
        return False
