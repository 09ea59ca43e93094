#!/usr/bin/env bash
# Build the catkin workspace (Release) with the system Python. Extra arguments go to catkin_make.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib/ros_env.sh
# Drop-ins (scripts/lib/dropins.py): a workspace xacro, gazebo_ros, ... is ignored where a real one exists.
/usr/bin/python3 scripts/lib/dropins.py apply --devel catkin_ws/devel > /dev/null
cd catkin_ws
catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_EXPORT_COMPILE_COMMANDS=ON "$@"
