#!/usr/bin/env bash
# The long soak of the simulator (issue #9): scripts/soak.py for [minutes] (default 30), JSON into
# bench_results/soak.json. Extra arguments go to soak.py and win over the ones given here (e.g. -v, --spawn-rate 4).
# Memory limit: 1 MiB/min after the warm-up (soak.py's default is 2 for its 60 s run): over the 24 minutes after a
# 30-minute run's warm-up a healthy simulator grows about 0.05 MiB/min, and 1 MiB/min is 24 MiB kept.
# Exits with soak.py's status: 0 when memory, threads and fds stayed flat and every spawn and delete succeeded.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)

minutes=30
if [ $# -gt 0 ] && [[ $1 != -* ]]; then
  minutes=$1
  shift
fi
if ! [[ $minutes =~ ^[0-9]+([.][0-9]+)?$ ]]; then
  echo "usage: scripts/soak.sh [minutes] [soak.py options]" >&2
  exit 2
fi

SOURCE_WORKSPACE="$repo/catkin_ws" . scripts/lib/ros_env.sh
# The soak starts a master of its own on a free port, never talks to one that happens to be running.
unset ROS_MASTER_URI

mkdir -p bench_results
duration=$(/usr/bin/python3 -c "import sys; print(float(sys.argv[1]) * 60)" "$minutes")
exec /usr/bin/python3 scripts/soak.py --duration "$duration" --json bench_results/soak.json \
  --max-rss-growth-mib-per-min 1 "$@"
