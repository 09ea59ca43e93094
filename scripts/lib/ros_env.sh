# Sourced by the scripts: the ROS environment with the system Python, whatever python3 is first on PATH.
export PATH="/usr/bin:/bin:$PATH"
# The scripts keep ROS on loopback unless the user chose otherwise (ROS 1 has no
# authentication: whoever reaches the master commands the robot).
export ROS_IP="${ROS_IP:-127.0.0.1}"
export ROS_HOSTNAME="${ROS_HOSTNAME:-$ROS_IP}"
_ros_env_nounset=$([[ $- == *u* ]] && echo 1 || true)
set +u
if [ -f /opt/ros/noetic/setup.bash ]; then . /opt/ros/noetic/setup.bash; fi
if [ -n "${SOURCE_WORKSPACE:-}" ] && [ -f "$SOURCE_WORKSPACE/devel/setup.bash" ]; then
  . "$SOURCE_WORKSPACE/devel/setup.bash"
fi
if [ -n "$_ros_env_nounset" ]; then set -u; fi
unset _ros_env_nounset
