#!/usr/bin/env python3
"""rostest node: one of gazebo_plugins' own rostests (ros-simulation/gazebo_ros_pkgs noetic-devel, registered in
gazebo_plugins/CMakeLists.txt), run unchanged against this workspace. Upstream's gazebo_plugins/test and
gazebo_plugins/scripts are written into a scratch package named gazebo_plugins (workspace_testing.upstream_tests),
built over our workspace (its gtest, if ~gtest_target names one), and rostest runs its ~test with
a master of its own; every test case it reports must pass.

The upstream repository is found as $GAZEBO_ROS_PKGS (a checkout or a git mirror) or a mirror cloned into
$ROS_HOME/upstream; where neither can be had the case is skipped, saying so, and its JUnit file says skipped
(workspace_testing.junit: rostest's own runner would write it as passed).

Params: ~test (the .test file in the package), ~gtest_target and ~gtest_sources (space-separated), ~components
(catkin packages the gtest builds with), ~opencv (OpenCV modules it links), ~timeout (s, build and run)."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import rospkg
import rospy
from workspace_testing.junit import run_node
from workspace_testing.processes import LoggedProcess
from workspace_testing.upstream_tests import GTest, ScratchPackage, find_upstream, read_results, shell_command

URL = "https://github.com/ros-simulation/gazebo_ros_pkgs"
BRANCH = "noetic-devel"
PACKAGE = "gazebo_plugins"


class UpstreamPluginTest(unittest.TestCase):
    def setUp(self) -> None:
        rospy.init_node("upstream_gazebo_plugins_test")
        self.test_file = rospy.get_param("~test")
        self.timeout = float(rospy.get_param("~timeout", 600.0))
        target = rospy.get_param("~gtest_target", "")
        gtests = ()
        if target:
            opencv = tuple(rospy.get_param("~opencv", "").split())
            libraries = ("${OpenCV_LIBRARIES}",) if opencv else ()
            sources = tuple(rospy.get_param("~gtest_sources").split())
            gtests = (GTest(target, self.test_file, sources, libraries),)
        components = tuple(rospy.get_param("~components", "roscpp").split())
        self.package = ScratchPackage(PACKAGE, components, tuple(rospy.get_param("~opencv", "").split()), gtests)
        self.scratch = tempfile.mkdtemp(prefix="upstream_gazebo_plugins_")

    def tearDown(self) -> None:
        shutil.rmtree(self.scratch, ignore_errors=True)

    def run_logged(self, command, timeout: float, env=None) -> subprocess.CompletedProcess:
        process = LoggedProcess(command, env=env)
        try:
            code = process.process.wait(timeout)
        except subprocess.TimeoutExpired:
            code = None
        output = process.output(20000)
        process.close()
        self.assertIsNotNone(code, f"{' '.join(command)} still running after {timeout} s:\n{output}")
        return subprocess.CompletedProcess(command, code, output)

    def test_upstream_test_passes(self) -> None:
        cache = os.path.join(rospkg.get_ros_home(), "upstream", "gazebo_ros_pkgs.git")
        source, where = find_upstream("GAZEBO_ROS_PKGS", URL, cache, BRANCH)
        if source is None:
            self.skipTest(where)
        rospy.loginfo("gazebo_plugins' tests from %s", where)
        files = source.files_under(f"{PACKAGE}/test")
        files.update(source.files_under(f"{PACKAGE}/scripts"))
        self.assertIn(f"{PACKAGE}/{self.test_file}", files, f"upstream has no {self.test_file}")
        self.package.write(os.path.join(self.scratch, "src", PACKAGE), files, PACKAGE)
        targets = [test.target for test in self.package.gtests]
        build = ["catkin_make", "-C", self.scratch, "-DCATKIN_ENABLE_TESTING=1", "-DCMAKE_BUILD_TYPE=Release"]
        built = self.run_logged(build + targets, self.timeout)
        self.assertEqual(built.returncode, 0, f"the scratch package does not build:\n{built.stdout}")
        results = os.path.join(self.scratch, "results")
        env = dict(os.environ, ROS_TEST_RESULTS_DIR=results)
        setup = os.path.join(self.scratch, "devel", "setup.bash")
        test_path = os.path.join(self.scratch, "src", PACKAGE, self.test_file)
        ran = self.run_logged(shell_command(setup, ["rostest", test_path]), self.timeout, env)
        found = read_results(results)
        self.assertGreater(found.tests, 0, f"no test case ran (skipped: {found.skipped}):\n{ran.stdout}")
        self.assertEqual(found.failed, [], f"\n{ran.stdout}")
        self.assertEqual(ran.returncode, 0, ran.stdout)


if __name__ == "__main__":
    sys.exit(run_node(UpstreamPluginTest, "upstream_gazebo_plugins", sys.argv))
