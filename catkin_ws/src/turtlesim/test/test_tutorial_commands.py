#!/usr/bin/env python3
"""rostest node: the commands of the ROS wiki beginner tutorials 5-8 (nodes, topics, services and parameters,
rqt_console and roslaunch), typed as the tutorials type them, against `rosrun turtlesim turtlesim_node` started
here the tutorials' way. The simulator runs headless (no DISPLAY), as it does on a machine without a screen."""
from __future__ import annotations

import math
import os
import re
import shlex
import subprocess
import sys
import tempfile
import threading
import time
import unittest
from typing import Callable, List, Optional

import rospy
import rostest
from rosgraph_msgs.msg import Log
from std_srvs.srv import Empty

from turtlesim.msg import Color, Pose
from turtlesim.srv import Spawn, TeleportAbsolute
from workspace_testing.processes import stop_group as stop

WORLD_SIZE = 499 / 45.0
CENTRE = WORLD_SIZE / 2.0
TWIST_ARC = "'[2.0, 0.0, 0.0]' '[0.0, 0.0, 1.8]'"
HEADLESS_ENV = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
HEADLESS_ENV.update(PYTHONUNBUFFERED="1", ROSCONSOLE_STDOUT_LINE_BUFFERED="1")


class Output:
    """A process's merged output, read by a thread, that a caller can wait on."""

    def __init__(self, process: subprocess.Popen):
        self.text = ""
        self._changed = threading.Condition()
        threading.Thread(target=self._read, args=(process,), daemon=True).start()

    def _read(self, process: subprocess.Popen) -> None:
        for line in process.stdout:
            with self._changed:
                self.text += line
                self._changed.notify_all()

    def wait_for(self, pattern: str, timeout: float) -> bool:
        with self._changed:
            return self._changed.wait_for(lambda: re.search(pattern, self.text, re.M) is not None, timeout)


class Recorder:
    """Every message of a topic with its arrival time; wait_until(predicate over the list)."""

    def __init__(self, topic: str, msg_type):
        self.messages: List = []
        self.times: List[float] = []
        self._changed = threading.Condition()
        self._sub = rospy.Subscriber(topic, msg_type, self._on_message, queue_size=100)

    def _on_message(self, msg) -> None:
        with self._changed:
            self.messages.append(msg)
            self.times.append(time.monotonic())
            self._changed.notify_all()

    def wait_until(self, predicate: Callable[[List], bool], timeout: float) -> bool:
        with self._changed:
            return self._changed.wait_for(lambda: predicate(self.messages), timeout)

    def snapshot(self) -> List:
        with self._changed:
            return list(self.messages)

    def close(self) -> None:
        self._sub.unregister()


def start(command: str, env: Optional[dict] = None) -> subprocess.Popen:
    return subprocess.Popen(
        shlex.split(command),
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        universal_newlines=True,
        start_new_session=True,
        env=env or HEADLESS_ENV,
    )


def stopped(poses: List[Pose], count: int = 10) -> bool:
    return len(poses) >= count and all(p.linear_velocity == 0.0 and p.angular_velocity == 0.0 for p in poses[-count:])


class TutorialCommands(unittest.TestCase):
    sim: subprocess.Popen
    sim_output: Output

    @classmethod
    def setUpClass(cls):
        cls.timeout = rospy.get_param("~command_timeout")
        cls.sim = start("rosrun turtlesim turtlesim_node")
        cls.sim_output = Output(cls.sim)
        for service in ("/spawn", "/clear", "/reset", "/kill", "/turtle1/teleport_absolute"):
            rospy.wait_for_service(service, cls.timeout)
        cls.reset = rospy.ServiceProxy("/reset", Empty)
        cls.spawn = rospy.ServiceProxy("/spawn", Spawn)

    @classmethod
    def tearDownClass(cls):
        stop(cls.sim)

    # --- helpers -------------------------------------------------------------------------------------------------
    def run_command(self, command: str, exit_code: Optional[int] = 0, shell: bool = False) -> str:
        """Run a tutorial command line to its end; return its stdout + stderr."""
        result = subprocess.run(
            command if shell else shlex.split(command),
            shell=shell,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            universal_newlines=True,
            timeout=self.timeout,
            env=HEADLESS_ENV,
            cwd=tempfile.gettempdir(),
        )
        if exit_code is not None:
            self.assertEqual(result.returncode, exit_code, "%s:\n%s" % (command, result.stdout))
        return result.stdout

    def fresh_world(self) -> None:
        """/reset (turtle1 alone in the middle, canvas cleared), and wait until turtle1 stands there again."""
        self.reset()
        rospy.wait_for_service("/turtle1/teleport_absolute", self.timeout)
        poses = Recorder("/turtle1/pose", Pose)
        try:
            at_centre = poses.wait_until(
                lambda p: stopped(p, 3) and abs(p[-1].x - CENTRE) < 1e-3 and abs(p[-1].y - CENTRE) < 1e-3,
                self.timeout,
            )
            self.assertTrue(at_centre, "turtle1 not standing in the middle after /reset")
        finally:
            poses.close()

    def assert_pose(self, pose: Pose, x: float, y: float, theta: float, tolerance: float = 1e-3) -> None:
        self.assertAlmostEqual(pose.x, x, delta=tolerance)
        self.assertAlmostEqual(pose.y, y, delta=tolerance)
        self.assertAlmostEqual(pose.theta, theta, delta=tolerance)

    # --- tutorial 5: nodes ---------------------------------------------------------------------------------------
    def test_headless_notice(self):
        self.assertTrue(self.sim_output.wait_for(r"running headless", self.timeout), self.sim_output.text)
        self.assertRegex(self.sim_output.text, r"no display \(DISPLAY is not set\)")
        self.assertRegex(self.sim_output.text, r"Spawning turtle \[turtle1\] at x=\[5\.54444\d\], y=\[5\.54444\d\]")

    def test_display_that_cannot_be_opened_runs_headless(self):
        env = dict(HEADLESS_ENV, DISPLAY=":987", ROS_NAMESPACE="bad_display")
        process = start("rosrun turtlesim turtlesim_node", env)
        try:
            output = Output(process)
            self.assertTrue(output.wait_for(r"running headless", self.timeout), output.text)
            self.assertRegex(output.text, r"cannot open display \[:987\]")
            rospy.wait_for_service("/bad_display/spawn", self.timeout)
        finally:
            stop(process)

    def test_bad_background_param_is_fatal_at_start_up(self):
        output = self.run_command(
            "rosrun turtlesim turtlesim_node __name:=bad_background __ns:=bad_background _background_r:=300",
            exit_code=1,
        )
        self.assertRegex(
            output,
            r"Parameter \[/bad_background/bad_background/background_r\] must be an integer in "
            r"\[0, 255\], got \[300\]",
        )

    def test_rosnode_list_info_ping(self):
        self.assertIn("/turtlesim", self.run_command("rosnode list").split())
        info = self.run_command("rosnode info /turtlesim")
        for line in (
            r"/turtle1/pose \[turtlesim/Pose\]",
            r"/turtle1/color_sensor \[turtlesim/Color\]",
            # A subscription nobody publishes to has no type at the master: rosnode says [unknown type] then.
            r"Subscriptions: \n \* /turtle1/cmd_vel \[(geometry_msgs/Twist|unknown type)\]",
            r"/rosout \[rosgraph_msgs/Log\]",
        ):
            self.assertRegex(info, line)
        for service in ("/clear", "/reset", "/spawn", "/kill", "/turtle1/set_pen", "/turtle1/teleport_absolute"):
            self.assertRegex(info, r"\* %s\n" % re.escape(service))
        self.assertRegex(self.run_command("rosnode ping -c 1 /turtlesim"), r"reply from http")

    # --- tutorial 6: topics ----------------------------------------------------------------------------------------
    def test_rostopic_list_type_echo_and_rosmsg(self):
        topics = self.run_command("rostopic list").split()
        for topic in ("/turtle1/cmd_vel", "/turtle1/color_sensor", "/turtle1/pose", "/rosout"):
            self.assertIn(topic, topics)
        self.assertEqual(self.run_command("rostopic type /turtle1/cmd_vel").strip(), "geometry_msgs/Twist")
        shown = self.run_command("rostopic type /turtle1/cmd_vel | rosmsg show", shell=True)
        self.assertRegex(shown, r"geometry_msgs/Vector3 linear\n\s+float64 x")
        echo = self.run_command("rostopic echo -n 1 /turtle1/pose")
        for field in ("x", "y", "theta", "linear_velocity", "angular_velocity"):
            self.assertRegex(echo, r"^%s: " % field if field == "x" else r"\n%s: " % field)
        self.assertEqual(self.run_command("rostopic type /turtle1/pose").strip(), "turtlesim/Pose")
        self.assertRegex(self.run_command("rosmsg show turtlesim/Pose"), r"float32 linear_velocity")

    def test_rostopic_hz_pose(self):
        process = start("rostopic hz /turtle1/pose")
        try:
            output = Output(process)
            self.assertTrue(output.wait_for(r"average rate: [\d.]+\n(.*\n){3}average rate", self.timeout), output.text)
            rates = [float(r) for r in re.findall(r"average rate: ([\d.]+)", output.text)]
            self.assertGreaterEqual(rates[-1], rospy.get_param("~min_pose_rate"), output.text)
            self.assertLessEqual(rates[-1], 70.0, "more poses than one per 16 ms update:\n" + output.text)
        finally:
            stop(process)

    def test_rostopic_pub_once_drives_an_arc_for_one_second(self):
        self.fresh_world()
        poses = Recorder("/turtle1/pose", Pose)
        try:
            self.assertTrue(poses.wait_until(lambda p: len(p) >= 3, self.timeout))
            start_count = len(poses.snapshot())
            self.run_command("rostopic pub -1 /turtle1/cmd_vel geometry_msgs/Twist -- " + TWIST_ARC)
            # rostopic pub -1 stays 3 s: the 1 s of motion is over by now, or nearly.
            done = poses.wait_until(
                lambda p: any(q.linear_velocity > 0 for q in p[start_count:]) and stopped(p, 20), self.timeout
            )
            self.assertTrue(done, "turtle1 did not move and then stop")
        finally:
            poses.close()
        recorded = poses.snapshot()
        moving = [p for p in recorded if p.linear_velocity > 0]
        for pose in moving:
            self.assertAlmostEqual(pose.linear_velocity, 2.0, places=5)
            self.assertAlmostEqual(pose.angular_velocity, 1.8, places=5)
        radius = 2.0 / 1.8
        tolerance = rospy.get_param("~arc_tolerance")
        for pose in recorded:  # the start faces +x, so the centre is a radius to its left
            self.assertAlmostEqual(math.hypot(pose.x - CENTRE, pose.y - (CENTRE + radius)), radius, delta=tolerance)
        final = recorded[-1]
        # 1 s of wall time at 1.8 rad/s, 62.5 updates of 16 ms (give or take the updates a busy machine drops).
        self.assertAlmostEqual(final.theta, 1.8, delta=rospy.get_param("~angle_tolerance"))
        for pose in recorded[-20:]:
            self.assert_pose(pose, final.x, final.y, final.theta, 0.0)

    def test_rostopic_pub_at_1_hz_keeps_the_turtle_moving(self):
        self.fresh_world()
        poses = Recorder("/turtle1/pose", Pose)
        process = start(
            "rostopic pub /turtle1/cmd_vel geometry_msgs/Twist -r 1 -- '[2.0, 0.0, 0.0]' '[0.0, 0.0, -1.8]'"
        )
        try:
            # Moving without a stop for 2.5 s: the 1 s timeout is refreshed by each message.
            def moved_long(p: List[Pose]) -> bool:
                times = poses.times[len(poses.times) - len(p) :]
                first = next((i for i, q in enumerate(p) if q.linear_velocity > 0), None)
                return (
                    first is not None
                    and all(q.linear_velocity > 0 for q in p[first:])
                    and (times[-1] - times[first] > 2.5)
                )

            self.assertTrue(poses.wait_until(moved_long, self.timeout), "turtle1 did not keep moving")
            self.assertAlmostEqual(poses.snapshot()[-1].angular_velocity, -1.8, places=5)
        finally:
            stop(process)
            poses.close()

    # --- tutorial 7: services and parameters -----------------------------------------------------------------------
    def test_rosservice_list_type_and_spawn(self):
        self.fresh_world()
        services = self.run_command("rosservice list").split()
        for service in (
            "/clear",
            "/kill",
            "/reset",
            "/spawn",
            "/turtle1/set_pen",
            "/turtle1/teleport_absolute",
            "/turtle1/teleport_relative",
            "/turtlesim/get_loggers",
            "/turtlesim/set_logger_level",
        ):
            self.assertIn(service, services)
        self.assertEqual(self.run_command("rosservice type /clear").strip(), "std_srvs/Empty")
        shown = self.run_command("rosservice type /spawn | rossrv show", shell=True)
        self.assertRegex(shown, r"float32 x\nfloat32 y\nfloat32 theta\nstring name\n---\nstring name")
        answer = self.run_command('rosservice call /spawn 2 2 0.2 ""')
        self.assertRegex(answer, r'name: "turtle2"')
        pose = rospy.wait_for_message("/turtle2/pose", Pose, self.timeout)
        self.assert_pose(pose, 2.0, 2.0, 0.2)
        duplicate = self.run_command('rosservice call /spawn 3 3 0 "turtle2"', exit_code=None)
        self.assertRegex(duplicate, r"ERROR")
        self.assertRegex(self.sim_output.text, r"A turtle named \[turtle2\] already exists")

    def test_rosservice_call_clear_with_rosparam_background(self):
        self.fresh_world()
        for name in ("/turtlesim/background_b", "/turtlesim/background_g", "/turtlesim/background_r"):
            self.assertIn(name, self.run_command("rosparam list").split())
        self.assertEqual(self.run_command("rosparam get /turtlesim/background_g").strip(), "86")
        colours = Recorder("/turtle1/color_sensor", Color)
        try:
            self.assertTrue(colours.wait_until(lambda c: c and (c[-1].r, c[-1].g, c[-1].b) == (69, 86, 255), 30))
            self.run_command("rosparam set /turtlesim/background_r 150")
            # The colour changes only on /clear, which reads the params.
            self.assertTrue(colours.wait_until(lambda c: len(c) >= 10 and c[-1].r == 69, self.timeout))
            self.run_command("rosservice call /clear")
            self.assertTrue(
                colours.wait_until(lambda c: (c[-1].r, c[-1].g, c[-1].b) == (150, 86, 255), self.timeout),
                "colour under turtle1 is not the new background",
            )
            params = self.run_command("rosparam get /")
            self.assertRegex(params, r"background_r: 150")
            self.run_command("rosparam dump params.yaml")
            self.run_command("rosparam load params.yaml copy_turtle")
            self.assertEqual(self.run_command("rosparam get /copy_turtle/turtlesim/background_b").strip(), "255")
        finally:
            colours.close()
            self.run_command("rosparam set /turtlesim/background_r 69")
            self.run_command("rosparam delete /copy_turtle")
            self.run_command("rosservice call /clear")

    def test_rosservice_call_reset(self):
        self.fresh_world()
        self.spawn(1.0, 1.0, 0.0, "turtle2")
        rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)(1.0, 8.0, 1.0)
        self.assert_pose(rospy.wait_for_message("/turtle2/pose", Pose, self.timeout), 1.0, 1.0, 0.0)
        self.run_command("rosservice call /reset")
        poses = Recorder("/turtle1/pose", Pose)
        try:
            self.assertTrue(poses.wait_until(lambda p: len(p) >= 1, self.timeout))
            self.assert_pose(poses.snapshot()[-1], CENTRE, CENTRE, 0.0)
        finally:
            poses.close()
        services = self.run_command("rosservice list").split()
        self.assertNotIn("/turtle2/set_pen", services)
        self.assertEqual(self.spawn(4.0, 4.0, 0.0, "").name, "turtle2")

    def test_rosservice_call_kill(self):
        self.fresh_world()
        self.spawn(2.0, 2.0, 0.0, "turtle2")
        self.run_command("rosservice call /kill turtle2")
        self.assertNotIn("/turtle2/set_pen", self.run_command("rosservice list").split())
        self.assertNotIn("/turtle2/pose", self.run_command("rostopic list").split())
        unknown = self.run_command("rosservice call /kill turtle2", exit_code=None)
        self.assertRegex(unknown, r"ERROR")
        self.assertRegex(self.sim_output.text, r"Tried to kill turtle \[turtle2\], which does not exist")

    def test_rosservice_call_set_pen_and_teleport(self):
        self.fresh_world()
        self.run_command("rosservice call /turtle1/set_pen 255 0 0 5 0")
        colours = Recorder("/turtle1/color_sensor", Color)
        try:
            self.run_command("rosservice call /turtle1/teleport_relative 1.0 0.0")
            self.assertTrue(colours.wait_until(lambda c: c and (c[-1].r, c[-1].g, c[-1].b) == (255, 0, 0), 30))
        finally:
            colours.close()
        self.run_command("rosservice call /turtle1/teleport_absolute 1 1 0")
        pose = rospy.wait_for_message("/turtle1/pose", Pose, self.timeout)
        self.assert_pose(pose, 1.0, 1.0, 0.0)

    # --- tutorial 8: rqt_console's subject, the wall warning on /rosout ------------------------------------------
    def test_wall_warning_on_rosout(self):
        self.fresh_world()
        rosout = Recorder("/rosout", Log)
        process = start(
            "rostopic pub /turtle1/cmd_vel geometry_msgs/Twist -r 1 -- "
            "'{linear: {x: 2.0, y: 0.0, z: 0.0}, angular: {x: 0.0,y: 0.0,z: 0.0}}'"
        )
        try:

            def warned(logs: List[Log]) -> bool:
                return any(
                    m.name == "/turtlesim" and m.level == Log.WARN and "Oh no! I hit the wall!" in m.msg for m in logs
                )

            self.assertTrue(rosout.wait_until(warned, self.timeout), "no wall warning on /rosout")
            pose = rospy.wait_for_message("/turtle1/pose", Pose, self.timeout)
            self.assertAlmostEqual(pose.x, WORLD_SIZE, places=4)
            warning = next(m.msg for m in rosout.snapshot() if "Oh no!" in m.msg)
            self.assertRegex(warning, r"^Oh no! I hit the wall! \(Clamping from \[x=\d+\.\d{6}, y=\d+\.\d{6}\]\)$")
        finally:
            stop(process)
            rosout.close()

    # --- tutorial 5 again, last: a second turtlesim_node takes over /spawn and the other world services ---------
    def test_zz_rosrun_with_name_remapping(self):
        process = start("rosrun turtlesim turtlesim_node __name:=my_turtle")
        try:
            output = Output(process)
            self.assertTrue(output.wait_for(r"Starting turtlesim with node name /my_turtle", self.timeout), output.text)
            self.assertIn("/my_turtle", self.run_command("rosnode list").split())
            self.assertRegex(self.run_command("rosnode ping -c 1 my_turtle"), r"reply from http")
        finally:
            stop(process)


if __name__ == "__main__":
    rospy.init_node("tutorial_commands")
    rostest.rosrun("turtlesim", "tutorial_commands", TutorialCommands, sys.argv)
