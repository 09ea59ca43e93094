#!/usr/bin/env python3
"""The run of scripts/demo.sh: demo.launch without its circle_demo (drive:=false) on a master of its own on a free
loopback port, the world paused until the TurtleBot is in, its output in a log; then circle_demo in the foreground,
once the simulator offers its services, so that the demo ends with its own last lines (the lap's summary and the
plot's path) rather than with roslaunch's shutdown; then the launch is stopped quietly. Everything it started is
stopped on exit, also on Ctrl-C and SIGTERM (scripts/lib/ros_run/processes.py). Exits with circle_demo's status, 1 if
the simulator did not start, 130 or 143 when interrupted."""
from __future__ import annotations

import argparse
import os
import signal
import sys
from typing import Optional, Sequence

from ros_run.master import service_offered

from turtle_sim_ode.analysis.waiting import wait_for
from ros_run.processes import Processes, free_port

CALLER_ID = "/demo"  # towards the master, before circle_demo exists
READY_SERVICE = "/gazebo/spawn_urdf_model"  # offered once the simulator is up: the launch's parameters are set
STARTUP_TIMEOUT_S = 60.0


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--gui", action="store_true", help="open rviz")
    parser.add_argument("--real-time-factor", type=float, default=0.0, help="0: as fast as possible (default)")
    parser.add_argument("--output", required=True, help="the plot (PNG)")
    parser.add_argument("--log", required=True, help="roslaunch's output goes here")
    args = parser.parse_args(argv)
    # Ctrl-C (SIGINT, even when the shell started us with it ignored) and SIGTERM unwind, so that every process group
    # started is stopped.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    os.environ["ROS_MASTER_URI"] = "http://127.0.0.1:%d" % free_port()  # never disturb a master the user has running
    env = dict(os.environ)
    log_dir, log_name = os.path.split(os.path.abspath(args.log))
    open(args.log, "w").close()  # this run's log only
    with Processes(log_dir) as processes:
        launch = processes.start(
            [
                "roslaunch",
                "turtle_sim_ode",
                "demo.launch",
                "drive:=false",
                "gui:=%s" % str(args.gui).lower(),
                "real_time_factor:=%g" % args.real_time_factor,
                "output:=" + os.path.abspath(args.output),
            ],
            env,
            log_name,
        )
        wait_for(lambda: service_offered(READY_SERVICE, CALLER_ID) or launch.poll() is not None, STARTUP_TIMEOUT_S)
        if launch.poll() is not None or not service_offered(READY_SERVICE, CALLER_ID):
            print(processes.log_tail(log_name, 30), file=sys.stderr)
            print("demo: the simulator did not start, see %s" % args.log, file=sys.stderr)
            return 1
        return processes.start(["rosrun", "turtle_sim_ode", "circle_demo"], env, None).wait()


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        print("\ndemo interrupted: every process started was stopped", file=sys.stderr)
        sys.exit(130)
