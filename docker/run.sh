#!/usr/bin/env bash
# Run the development container (docker/Dockerfile, stage "dev") with this repository mounted at the same path as on
# the host, so build folders and catkin_ws/build/compile_commands.json are valid on both sides.
#
#   docker/run.sh [--network-host] [--no-build] [--base IMAGE] [COMMAND ...]     (default COMMAND: bash)
#   docker/run.sh                      # a shell; then: scripts/build.sh, roslaunch ..., rviz
#   docker/run.sh scripts/test.sh      # the whole test suite in the container
#
# Engine: docker when its daemon answers, else podman (CONTAINER_ENGINE=docker|podman chooses). The image is built
# (cached) with your UID/GID so that files the container writes into the repository are yours; with rootless
# podman, --userns=keep-id maps your UID to the same UID in the container. As root on the host the container runs as
# root too.
#
# X11 (rviz): when DISPLAY is set, /tmp/.X11-unix is mounted, DISPLAY passed, and a copy of your X cookie valid for
# any host name is mounted as XAUTHORITY (needs `xauth` on the host); /dev/dri is passed when present (GPU
# rendering). If the X server still refuses the connection, allow your user on it: xhost +SI:localuser:$(id -un)
# A DISPLAY such as localhost:10.0 (ssh -X) is a TCP port on the host's loopback: add --network-host.
#
# ROS networking: loopback only (ROS_IP=127.0.0.1, ROS_HOSTNAME=ROS_IP) unless you set ROS_IP / ROS_HOSTNAME /
# ROS_MASTER_URI on the host: they are passed in. To talk to other machines use the host's network and address:
#   ROS_IP=192.168.1.20 ROS_MASTER_URI=http://192.168.1.10:11311 docker/run.sh --network-host
# (ROS 1 has no authentication: whoever reaches the master commands the robot; open it on trusted networks only.)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)

network_host=0
build=1
base=""
while [ "$#" -gt 0 ]; do
  case "$1" in
    --network-host) network_host=1 ;;
    --no-build) build=0 ;;
    --base) base=$2; shift ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    --) shift; break ;;
    *) break ;;
  esac
  shift
done
[ "$#" -gt 0 ] || set -- bash

engine=${CONTAINER_ENGINE:-}
if [ -z "$engine" ]; then
  if command -v docker > /dev/null && docker info > /dev/null 2>&1; then engine=docker
  elif command -v podman > /dev/null; then engine=podman
  elif command -v docker > /dev/null; then engine=docker  # its own error says why the daemon does not answer
  else echo "run.sh: neither docker nor podman found" >&2; exit 1; fi
fi

uid=$(id -u)
gid=$(id -g)
image=${RUN_IMAGE:-turtle_sim_ode-dev:latest}
build_args=(--build-arg "USER_UID=$uid" --build-arg "USER_GID=$gid")
run_args=(--rm --security-opt label=disable -v "$repo:$repo" -w "$repo" -e "REPO_DIR=$repo")
if [ "$uid" -eq 0 ] || [ "$gid" -eq 0 ]; then
  build_args=()  # the image keeps its default user; the container runs as root like its caller
  run_args+=(--user 0:0 -e HOME=/root)
fi
[ -z "$base" ] || build_args+=(--build-arg "BASE=$base")
if [ "$engine" = podman ]; then
  build_args+=(--format docker)  # the OCI format would ignore the Dockerfile's SHELL
  [ "$uid" -eq 0 ] || run_args+=(--userns=keep-id)
fi
if [ -t 0 ] && [ -t 1 ]; then run_args+=(-it); else run_args+=(-i); fi
[ "$network_host" -eq 0 ] || run_args+=(--network host)

for variable in ROS_IP ROS_HOSTNAME ROS_MASTER_URI; do
  [ -z "${!variable:-}" ] || run_args+=(-e "$variable")
done

# X11 forwarding for rviz and other GUIs.
if [ -n "${DISPLAY:-}" ]; then
  run_args+=(-e DISPLAY -e QT_X11_NO_MITSHM=1)
  [ ! -d /tmp/.X11-unix ] || run_args+=(-v /tmp/.X11-unix:/tmp/.X11-unix:ro)
  if command -v xauth > /dev/null; then
    # The cookie with its host name replaced by a wildcard (family ffff): valid inside the container.
    xauth_file="${XDG_RUNTIME_DIR:-/tmp}/turtle_sim_ode-$uid.xauth"
    touch "$xauth_file"
    chmod 0644 "$xauth_file"  # readable by the container's user (same UID, or a mapped one)
    xauth nlist "$DISPLAY" 2> /dev/null | sed -e 's/^..../ffff/' | xauth -f "$xauth_file" nmerge - 2> /dev/null || true
    run_args+=(-e XAUTHORITY=/tmp/.container.xauth -v "$xauth_file:/tmp/.container.xauth:ro")
  fi
  [ ! -d /dev/dri ] || run_args+=(--device /dev/dri)
fi

if [ "$build" -eq 1 ]; then
  "$engine" build -f "$repo/docker/Dockerfile" --target dev -t "$image" "${build_args[@]}" "$repo"
fi
exec "$engine" run "${run_args[@]}" "$image" "$@"
