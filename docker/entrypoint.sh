#!/usr/bin/env bash
# Container entrypoint: the ROS environment, then the command (an interactive bash by default).
# /etc/bash.bashrc also sources this file, so shells started with `docker exec` or by VS Code get the same setup.
#
# ROS networking stays on loopback unless the user opens it: docker run -e ROS_IP=<host ip> (docker/README.md).
export ROS_IP="${ROS_IP:-127.0.0.1}"
export ROS_HOSTNAME="${ROS_HOSTNAME:-$ROS_IP}"

# ROS itself: /opt/ros/noetic on Ubuntu (ros:noetic base); Debian's packages live under /usr and need nothing.
if [ -f /opt/ros/noetic/setup.bash ]; then
  # shellcheck disable=SC1091
  . /opt/ros/noetic/setup.bash
fi

# The workspace: $REPO_DIR if given, else the repository in the current directory (docker/run.sh and the dev
# container mount it there), else the one built into the image.
for _repo in "${REPO_DIR:-}" "$PWD" /workspace; do
  if [ -n "$_repo" ] && [ -f "$_repo/catkin_ws/devel/setup.bash" ]; then
    # shellcheck disable=SC1091
    . "$_repo/catkin_ws/devel/setup.bash"
    break
  fi
done
unset _repo

if [ "${BASH_SOURCE[0]}" = "$0" ]; then
  [ "$#" -gt 0 ] || set -- bash
  exec "$@"
fi
