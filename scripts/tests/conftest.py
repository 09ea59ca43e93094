"""Helpers shared by the workspace tests that start ROS processes; scripts/lib (the tools' modules) on the path."""
import json
import os
import shutil
import subprocess
import sys

ROS_PYTHON = "/usr/bin/python3"
LIB = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "lib"))
if LIB not in sys.path:
    sys.path.insert(0, LIB)


def ros_missing():
    """Why ROS and this workspace cannot run here (a reason to skip), or None."""
    if not os.access(ROS_PYTHON, os.X_OK):
        return ROS_PYTHON + " not found"
    if not shutil.which("roscore") or not shutil.which("roslaunch"):
        return "roscore/roslaunch not on PATH: source catkin_ws/devel/setup.bash"
    result = subprocess.run(
        [ROS_PYTHON, "-c", "import rospy, gazebo_msgs.srv, turtle_sim_ode"],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        universal_newlines=True,
    )
    if result.returncode != 0:
        return "ROS or the workspace is not importable by %s (source catkin_ws/devel/setup.bash): %s" % (
            ROS_PYTHON,
            result.stdout.strip().splitlines()[-1],
        )
    return None


def run_bench(script, args, json_path, marker, timeout):
    """Run scripts/``script`` with ``args`` and ``--json json_path`` on the ROS Python (skipped where ROS is missing)
    and return the JSON it wrote; the test fails, with the end of its output, if it overruns ``timeout`` s (then it
    gets SIGTERM: the benchmarks stop their masters and nodes on it), exits non-zero or never prints ``marker``."""
    import pytest

    reason = ros_missing()
    if reason:
        pytest.skip(reason)
    command = [ROS_PYTHON, os.path.join(os.path.dirname(LIB), script)] + list(args) + ["--json", json_path]
    bench = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    try:
        output, _ = bench.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        bench.terminate()
        output, _ = bench.communicate()
        pytest.fail("%s %s took over %d s:\n%s" % (script, " ".join(args), timeout, output[-5000:]))
    assert bench.returncode == 0, output[-5000:]
    assert marker in output, output[-5000:]
    with open(json_path) as json_file:
        return json.load(json_file)
