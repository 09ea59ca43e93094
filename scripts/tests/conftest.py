"""Helpers shared by the workspace tests that start ROS processes; scripts/lib (the tools' modules) on the path."""
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
