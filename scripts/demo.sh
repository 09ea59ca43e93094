#!/usr/bin/env bash
# Install what is missing, build, and run the TurtleBot demo: the simulator headless and as fast as it can go,
# the robot driving a circle with a live progress line, then a PNG plot of wheel odometry against ground truth.
#   scripts/demo.sh          headless
#   scripts/demo.sh --gui    real time, with the viewer showing the world and the robot (needs a display)
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)

gui=false
for arg in "$@"; do
  case "$arg" in
    --gui) gui=true ;;
    -h|--help) sed -n '2,5p' "$0"; exit 0 ;;
    *) echo "demo.sh: unknown argument '$arg' (try --help)" >&2; exit 2 ;;
  esac
done
if [ "$gui" = true ] && [ -z "${DISPLAY:-}" ]; then
  echo "demo.sh: --gui needs a display (DISPLAY is not set); run without --gui for the headless demo" >&2
  exit 2
fi

scripts/install_deps.sh
echo "Building the workspace (log: build.log) ..."
scripts/build.sh > build.log 2>&1 || { tail -40 build.log; echo "demo.sh: build failed, see build.log" >&2; exit 1; }
SOURCE_WORKSPACE="$repo/catkin_ws" . scripts/lib/ros_env.sh

mkdir -p results
real_time_factor=0
if [ "$gui" = true ]; then real_time_factor=1; fi
# The world in the background on a master of its own (a free loopback port), its output in results/demo_launch.log;
# circle_demo in the foreground, so that the demo ends with its summary and the plot's path; all stopped at the end.
echo "Starting the simulator (log: results/demo_launch.log) ..."
gui_flag=()
if [ "$gui" = true ]; then gui_flag=(--gui); fi
exec /usr/bin/python3 scripts/lib/run_demo.py "${gui_flag[@]}" --real-time-factor "$real_time_factor" \
  --output "$repo/results/demo_circle.png" --log "$repo/results/demo_launch.log"
