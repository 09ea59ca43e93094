"""gazebo_ros's rosrun entry points (gzserver, gazebo, gzclient, debug, perf) on turtle_sim_ode: each reads
Gazebo's command line (see command_line) and runs the simulator as node `gazebo` in this process, or the viewer.

The simulator runs in the calling process (roslaunch watches its pid; `required` and `respawn` work as with
Gazebo's scripts); the viewer is turtle_sim_ode's (rviz on the world's scene and a control window), started where
there is a display.
"""
from __future__ import annotations

import cProfile
import faulthandler
import os
import shutil
import signal
import subprocess
import sys
import threading
from typing import List, Optional, Sequence


from gazebo_ros_dropin import display_problem
from gazebo_ros_dropin.command_line import CommandLineError, parse_server_args, split_ros_arguments, usage

VERSION = "turtle_sim_ode (the gazebo_ros drop-in): Gazebo classic's ROS API on ODE"


# The viewer: rviz on the world as Gazebo's client shows it, beside a control window (turtle_sim_ode.ros.viewer).
VIEWER = ["rosrun", "turtle_sim_ode", "viewer"]


def ros_arguments(argv: Sequence[str]) -> List[str]:
    return [arg for arg in argv if ":=" in arg]


def run_server(argv: Sequence[str], program: str) -> int:
    """gzserver: the simulator as node `gazebo` on the command line's world, until it is stopped."""
    try:
        options = parse_server_args(split_ros_arguments(argv))
    except CommandLineError as error:
        print("%s: %s" % (program, error), file=sys.stderr)
        return 255  # gzserver's exit status for arguments it cannot run with
    if options.help:
        print(usage(program, "simulation server"))
        return 0
    if options.version:
        print(VERSION)
        return 0
    notes = ["%s: %s" % (program, note) for note in options.notes]
    if options.verbose:  # Gazebo prints its version and the messages it keeps quiet otherwise
        print("%s\n%s: world [%s]%s" % (VERSION, program, options.world, ", paused" if options.paused else ""))
    from turtle_sim_ode.ros.node import main  # imports rospy and the simulator: only when a server is wanted

    return main({"world_name": options.world, "paused": options.paused}, notes, claim_sim_time=True)


def run_gazebo(argv: Sequence[str]) -> int:
    """gazebo: the server, and the viewer where there is a display; closing the viewer stops the server, as
    gazebo_ros's script sends SIGINT to gzserver when gzclient ends."""
    client: Optional[subprocess.Popen] = None
    problem = display_problem(os.environ)
    if problem is None and not any(arg in ("-h", "--help", "-v", "--version") for arg in argv):
        # No remapping of the command line: those are the server's (its __name:= would name the viewer too).
        client = subprocess.Popen(VIEWER, stdin=subprocess.DEVNULL)
        threading.Thread(target=_stop_server_after, args=(client,), daemon=True).start()
    elif problem is not None:
        print("gazebo: %s: no viewer (gzclient), the simulation runs headless" % problem, file=sys.stderr)
    try:
        return run_server(argv, "gazebo")
    finally:
        if client is not None and client.poll() is None:
            client.send_signal(signal.SIGINT)
            try:
                client.wait(10)
            except subprocess.TimeoutExpired:
                client.kill()
                client.wait()


def _stop_server_after(client: subprocess.Popen) -> None:
    client.wait()
    os.kill(os.getpid(), signal.SIGINT)  # the server's handler stops its loop


def run_client(
    argv: Sequence[str],
    config: Optional[str] = None,
    notice: str = "gzclient: %s: no viewer; the simulation runs headless",
) -> int:
    """gzclient: the viewer (node `gazebo_gui`, with an anonymous suffix unless named, so several may run) where
    there is a display, on rviz ``config`` if given; without one the ``notice`` (with the reason) as a warning, and
    the node stays up doing nothing, so that a launch file's required="true" viewer does not end the launch."""
    problem = display_problem(os.environ)
    remaps = ros_arguments(argv)
    if problem is None:
        os.execvp(VIEWER[0], VIEWER + ([config] if config else []) + remaps)
    import rospy

    rospy.init_node("gazebo_gui")
    rospy.logwarn(notice, problem)
    ignored = [arg for arg in argv if ":=" not in arg]
    if ignored:
        rospy.logwarn("gzclient: arguments %s ignored: the viewer is rviz on the world", ignored)
    rospy.spin()  # returns at shutdown; it raises no ROSInterruptException (rospy/client.py, spin)
    return 0


def run_debug(argv: Sequence[str], gzserver: str) -> int:
    """debug: gzserver under gdb (as gazebo_ros's gdbrun: gdb runs it at once), which catches a crash in ODE or
    the C kernels with a backtrace; without gdb, Python's faulthandler prints the stack on a fatal signal."""
    gdb = shutil.which("gdb")
    if gdb is not None:
        # At a terminal gdb stays at its prompt after a crash; without one (roslaunch, tests) it prints the
        # backtrace and ends with the server.
        commands = ["-ex", "run"] if sys.stdin.isatty() else ["-batch", "-ex", "run", "-ex", "bt"]
        os.execv(gdb, [gdb] + commands + ["--args", sys.executable, gzserver] + list(argv))
    print("debug: gdb is not installed: running gzserver with Python's faulthandler instead", file=sys.stderr)
    faulthandler.enable()
    return run_server(argv, "debug")


def run_perf(argv: Sequence[str]) -> int:
    """perf: gzserver under a profiler (gazebo_ros runs valgrind's callgrind on the C++ server; here Python's
    cProfile, whose statistics are written to $ROS_HOME/gzserver.prof when the server stops)."""
    home = os.environ.get("ROS_HOME", os.path.join(os.path.expanduser("~"), ".ros"))
    os.makedirs(home, exist_ok=True)
    path = os.path.join(home, "gzserver.prof")
    profile = cProfile.Profile()
    try:
        return profile.runcall(run_server, argv, "perf")
    finally:
        profile.dump_stats(path)
        print("perf: profile written to %s (read it with: python3 -m pstats %s)" % (path, path), file=sys.stderr)
