#!/usr/bin/env python3
"""rostest node: turtlesim_node under Xvfb shows its window: a screenshot has the background colour, a trail in the
default pen colour where turtle1 went, one in a set_pen colour, and the drawn turtle."""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
import unittest

import numpy as np
import rospy
import rostest

# The screenshot reader of the workspace's simulator. Not a <test_depend>: turtle_sim_ode test-depends on
# beginner_tutorials, which runs turtlesim, so catkin would see a cycle; both are built in this workspace.
from workspace_testing.xwd_image import read_xwd
from turtlesim.msg import Pose
from turtlesim.srv import SetPen, TeleportAbsolute
from workspace_testing.processes import stop_group as stop
from workspace_testing.screen import start_xvfb

BACKGROUND = (69, 86, 255)
PEN = (179, 184, 255)
RED = (255, 0, 0)
CANVAS = 500
PIXELS_PER_METRE = 45.0
WORLD_SIZE = (CANVAS - 1) / PIXELS_PER_METRE


def matches(image: np.ndarray, colour, tolerance: int) -> np.ndarray:
    return np.all(np.abs(image.astype(int) - colour) <= tolerance, axis=2)


def to_pixel(x: float, y: float):
    """World metres -> (row, column) on the canvas."""
    return int(round((WORLD_SIZE - y) * PIXELS_PER_METRE)), int(round(x * PIXELS_PER_METRE))


class WindowShowsCanvas(unittest.TestCase):
    def test_background_trails_and_turtle(self):
        timeout = rospy.get_param("~timeout")
        tolerance = rospy.get_param("~colour_tolerance")
        xvfb, display = start_xvfb()
        log_path = os.path.join(tempfile.gettempdir(), "turtlesim_window_node.log")
        shot_path = os.path.join(tempfile.gettempdir(), "turtlesim_window.png")
        with open(log_path, "w") as log:
            node = subprocess.Popen(
                ["rosrun", "turtlesim", "turtlesim_node"],
                env=dict(os.environ, DISPLAY=display),
                stdout=log,
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )
        try:
            rospy.wait_for_service("/turtle1/teleport_absolute", timeout)
            teleport = rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)
            set_pen = rospy.ServiceProxy("/turtle1/set_pen", SetPen)

            def teleport_and_wait(x: float, y: float) -> None:
                """Teleports wait for the next update; set_pen acts at once: let the trail be drawn first."""
                teleport(x, y, 0.0)
                pose = rospy.wait_for_message("/turtle1/pose", Pose, timeout)
                while abs(pose.x - x) > 1e-3 or abs(pose.y - y) > 1e-3:
                    pose = rospy.wait_for_message("/turtle1/pose", Pose, timeout)

            # A default-pen trail along y = 2 m from x = 2 to 5, then a red one along y = 4 m.
            teleport_and_wait(2.0, 2.0)
            teleport_and_wait(5.0, 2.0)
            set_pen(255, 0, 0, 5, 0)
            teleport_and_wait(5.0, 4.0)
            teleport_and_wait(2.0, 4.0)
            teleport_and_wait(8.0, 8.0)  # the turtle itself, away from the trails

            probes = {
                "background": (to_pixel(8.0, 2.0), BACKGROUND),
                "default pen trail": (to_pixel(3.5, 2.0), PEN),
                "set_pen trail": (to_pixel(3.5, 4.0), RED),
            }
            deadline = time.monotonic() + timeout
            image, origin, failures, grab_error = None, None, ["no screenshot"], ""
            while time.monotonic() < deadline and failures:
                self.assertIsNone(node.poll(), "turtlesim_node exited:\n" + open(log_path).read())
                grab = subprocess.run(
                    ["xwd", "-root", "-silent", "-display", display], stdout=subprocess.PIPE, stderr=subprocess.PIPE
                )
                if grab.returncode != 0:  # the window may be mapping: the next try decides
                    grab_error = grab.stderr.decode(errors="replace").strip()
                    time.sleep(0.5)  # nothing to wait on but the picture
                    continue
                image = read_xwd(grab.stdout)
                failures = []
                ys, xs = np.nonzero(matches(image, BACKGROUND, tolerance))
                if len(xs) < CANVAS * CANVAS // 2:
                    failures.append("background: %d pixels of %s" % (len(xs), BACKGROUND))
                else:
                    origin = (ys.min(), xs.min())  # the canvas' top-left corner on the screen
                    if (ys.max() - ys.min() + 1, xs.max() - xs.min() + 1) != (CANVAS, CANVAS):
                        failures.append("canvas is %dx%d" % (xs.max() - xs.min() + 1, ys.max() - ys.min() + 1))
                    for what, ((row, column), colour) in probes.items():
                        seen = image[origin[0] + row, origin[1] + column]
                        if not matches(seen[None, None, :], colour, tolerance)[0, 0]:
                            failures.append("%s at (%d, %d): %s, expected %s" % (what, row, column, seen, colour))
                    row, column = to_pixel(8.0, 8.0)
                    patch = image[
                        origin[0] + row - 8 : origin[0] + row + 9, origin[1] + column - 8 : origin[1] + column + 9
                    ]
                    turtle = np.count_nonzero(~matches(patch, BACKGROUND, 30))
                    if turtle < 100:
                        failures.append("turtle at (%d, %d): %d non-background pixels" % (row, column, turtle))
                if failures:
                    time.sleep(0.5)  # the window draws in its own time
            self.assertIsNotNone(image, "no screenshot of %s; last xwd error: %s" % (display, grab_error))
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot as plt

            plt.imsave(shot_path, image)
            self.assertEqual(failures, [], "screenshot %s; node log:\n%s" % (shot_path, open(log_path).read()))
            self.assertNotRegex(open(log_path).read(), r"running headless")
        finally:
            stop(node)
            stop(xvfb)


if __name__ == "__main__":
    rospy.init_node("test_window_render")
    rostest.rosrun("turtlesim", "window_render", WindowShowsCanvas, sys.argv)
