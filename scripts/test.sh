#!/usr/bin/env bash
# Install what is missing, build, run every suite (pytest, gtest, rostest) and print one closing line
# "N passed, N failed, N skipped". Exits non-zero on any failure or when no test ran.
set -uo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)

scripts/install_deps.sh || exit 1
scripts/build.sh > build.log 2>&1 || { tail -50 build.log; echo "build failed (build.log)"; exit 1; }
SOURCE_WORKSPACE="$repo/catkin_ws" . scripts/lib/ros_env.sh
# Every test talks to masters it starts itself, never to one that happens to be running.
unset ROS_MASTER_URI

results="$repo/catkin_ws/build/test_results"
rm -rf "$results"
mkdir -p "$results/pytest"

echo "== pytest: ROS-free unit tests and workspace checks"
for suite in catkin_ws/src/*/test/unit scripts/tests; do
  [ -d "$suite" ] || continue
  name=$(echo "$suite" | tr '/' '_')
  /usr/bin/python3 -m pytest -q -p no:cacheprovider "$suite" --junitxml="$results/pytest/$name.xml"
done

echo "== gtest and rostest (catkin_make run_tests)"
(cd catkin_ws && catkin_make run_tests -j2 > "$repo/run_tests.log" 2>&1)
run_tests_status=$?
if [ "$run_tests_status" -ne 0 ]; then
  # A test target that does not build leaves no result file of its own: record the failure.
  printf '<testsuite name="run_tests"><testcase classname="catkin_make" name="run_tests"><failure message="exit %s, see run_tests.log"/></testcase></testsuite>\n' \
    "$run_tests_status" > "$results/run_tests_exit.xml"
fi
grep -E "^\[ *(OK|FAILED|PASSED) *\]|^\[ROSTEST\]|^ *\* (SUMMARY|RESULT)|^ *\* FAILURES|^ *\* ERRORS" run_tests.log || true

echo "== summary"
/usr/bin/python3 scripts/lib/summarize_results.py "$results"
