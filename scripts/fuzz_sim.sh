#!/usr/bin/env bash
# The simulator's property-based fuzz suite (catkin_ws/src/turtle_sim_ode/test/unit/test_fuzz.py) with many more
# examples than CI runs, and fresh random inputs unless a seed is given.
#   scripts/fuzz_sim.sh [examples] [seed]    default 5000 examples a test, a random seed
set -euo pipefail
cd "$(dirname "$0")/.."
examples=${1:-5000}
seed=${2:-$RANDOM}
SOURCE_WORKSPACE="$PWD/catkin_ws" . scripts/lib/ros_env.sh
echo "fuzz_sim: $examples examples a test, seed $seed"
TURTLE_SIM_FUZZ_EXAMPLES="$examples" TURTLE_SIM_FUZZ_SEED="$seed" /usr/bin/python3 -m pytest -q -p no:cacheprovider \
  catkin_ws/src/turtle_sim_ode/test/unit/test_fuzz.py catkin_ws/src/turtle_sim_ode/test/unit/test_camera_fuzz.py \
  catkin_ws/src/turtle_sim_ode/test/unit/test_mesh_fuzz.py catkin_ws/src/turtlesim/test/unit/test_turtlesim_fuzz.py \
  catkin_ws/src/xacro/test/unit/test_sandbox_fuzz.py \
  --hypothesis-show-statistics
