#!/usr/bin/env bash
# The property-based fuzz suites (the simulator's test_fuzz.py, test_camera_fuzz.py and test_mesh_fuzz.py, turtlesim's
# test_turtlesim_fuzz.py, the xacro sandbox's test_sandbox_fuzz.py) with many more examples than CI runs, and fresh
# random inputs unless a seed is given.
#   scripts/fuzz_sim.sh [examples] [seed]    default 5000 examples a test, a random seed
set -euo pipefail
cd "$(dirname "$0")/.."
examples=${1:-5000}
seed=${2:-$RANDOM}
SOURCE_WORKSPACE="$PWD/catkin_ws" . scripts/lib/ros_env.sh
echo "fuzz_sim: $examples examples a test, seed $seed"
export TURTLE_SIM_FUZZ_EXAMPLES="$examples" TURTLE_SIM_FUZZ_SEED="$seed"
# One pytest per package: each package's test/unit has a conftest.py of its own.
status=0
for suites in \
  "catkin_ws/src/turtle_sim_ode/test/unit/test_fuzz.py catkin_ws/src/turtle_sim_ode/test/unit/test_camera_fuzz.py
   catkin_ws/src/turtle_sim_ode/test/unit/test_mesh_fuzz.py" \
  catkin_ws/src/turtlesim/test/unit/test_turtlesim_fuzz.py \
  catkin_ws/src/xacro/test/unit/test_sandbox_fuzz.py; do
  # shellcheck disable=SC2086  # the list of files is split on purpose
  /usr/bin/python3 -m pytest -q -p no:cacheprovider $suites --hypothesis-show-statistics || status=1
done
exit $status
