#!/usr/bin/env python3
"""rostest node: runs command lines against the test's master and checks their exit code and output.

Each entry of ~cases becomes one test:
  name:      test name (test_<name>)
  command:   a command line (split like a shell would, no shell features)
  exit_code: the expected exit code (default 0), or "running": the command must still be running once every
             pattern has been seen; it is then stopped with SIGINT
  expect:    regular expressions that must all appear in stdout + stderr (multiline)
  params:    {name: value} that must be on the parameter server once the patterns were seen ("running" only)
  reject:    regular expressions that must not appear
  timeout:   seconds (default 20)
"""
import os
import re
import shlex
import subprocess
import sys
import threading
import unittest

import rospy
import rostest
from workspace_testing.processes import stop_group as stop


class CommandOutput:
    """Collects a process's merged output from a reader thread, so that a caller can wait for patterns."""

    def __init__(self, process: subprocess.Popen):
        self.text = ""
        self._changed = threading.Condition()
        self._thread = threading.Thread(target=self._read, args=(process,), daemon=True)
        self._thread.start()

    def _read(self, process):
        for line in process.stdout:
            with self._changed:
                self.text += line
                self._changed.notify_all()

    def wait_for(self, patterns, timeout: float) -> bool:
        with self._changed:
            return self._changed.wait_for(lambda: all(re.search(p, self.text, re.M) for p in patterns), timeout)

    def finish(self, timeout: float) -> None:
        self._thread.join(timeout)


def run_case(test: unittest.TestCase, case: dict) -> None:
    timeout = float(case.get("timeout", 20))
    expected_exit = case.get("exit_code", 0)
    # Nodes write into a pipe here: make them flush each line, as they would on a terminal.
    env = dict(os.environ, ROSCONSOLE_STDOUT_LINE_BUFFERED="1", PYTHONUNBUFFERED="1")
    process = subprocess.Popen(
        shlex.split(case["command"]),
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        universal_newlines=True,
        start_new_session=True,
        env=env,
    )
    output = CommandOutput(process)
    try:
        if expected_exit == "running":
            seen = output.wait_for(case.get("expect", []), timeout)
            test.assertIsNone(process.poll(), "command ended early (exit %s):\n%s" % (process.poll(), output.text))
            test.assertTrue(seen, "patterns %s not seen within %s s:\n%s" % (case.get("expect"), timeout, output.text))
            for name, value in case.get("params", {}).items():
                test.assertEqual(rospy.get_param(name, None), value, "parameter %s" % name)
        else:
            try:
                exit_code = process.wait(timeout)
            except subprocess.TimeoutExpired:
                test.fail("command still running after %s s:\n%s" % (timeout, output.text))
            output.finish(5.0)
            test.assertEqual(exit_code, int(expected_exit), "wrong exit code; output:\n%s" % output.text)
            for pattern in case.get("expect", []):
                test.assertRegex(output.text, re.compile(pattern, re.M))
        for pattern in case.get("reject", []):
            test.assertNotRegex(output.text, re.compile(pattern, re.M))
    finally:
        stop(process)


def make_test(case: dict):
    return lambda self: run_case(self, case)


class CommandCases(unittest.TestCase):
    pass


if __name__ == "__main__":
    rospy.init_node("run_commands", anonymous=True)
    for case in rospy.get_param("~cases"):
        setattr(CommandCases, "test_" + case["name"], make_test(case))
    rostest.rosrun("beginner_tutorials", "run_commands", CommandCases, sys.argv)
