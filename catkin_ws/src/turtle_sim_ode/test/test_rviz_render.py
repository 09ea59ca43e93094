#!/usr/bin/env python3
"""rostest node: start Xvfb and rviz on the shipped config, take screenshots until enough pixels of ``~colour``
show in the middle of the 3D view (or time runs out), and keep the last screenshot as a PNG (``~screenshot``, in
the temp directory) for people to look at. Blue: the TurtleBot's shell (rviz.test); red: the point cloud of a red
box (rviz_camera.test)."""
import os
import subprocess
import sys
import tempfile
import time
import unittest

import matplotlib
import numpy as np
import rospy
import rostest

from workspace_testing.xwd_image import read_xwd

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from workspace_testing.processes import stop_group as stop
from workspace_testing.screen import start_xvfb

RVIZ_BACKGROUND = (48, 48, 48)


def robot_pixels(image, colour="blue"):
    """Pixels of ``colour`` (blue or red) inside the central half of the 3D view (the region of rviz's background
    colour)."""
    view = np.all(np.abs(image.astype(int) - RVIZ_BACKGROUND) <= 2, axis=2)
    ys, xs = np.nonzero(view)
    if len(xs) == 0:
        return 0
    x0, x1, y0, y1 = xs.min(), xs.max(), ys.min(), ys.max()
    cx0, cx1 = x0 + (x1 - x0) // 4, x1 - (x1 - x0) // 4
    cy0, cy1 = y0 + (y1 - y0) // 4, y1 - (y1 - y0) // 4
    r, g, b = [image[cy0:cy1, cx0:cx1, i].astype(int) for i in range(3)]
    if colour == "red":
        return int(np.count_nonzero((r > g + 60) & (r > b + 60)))
    return int(np.count_nonzero((b > r + 60) & (b > g + 20)))


def tail(path, lines=15):
    with open(path, errors="replace") as log:
        return "".join(log.readlines()[-lines:])


class RvizShowsRobot(unittest.TestCase):
    def test_robot_visible(self):
        xvfb, display = start_xvfb()
        env = dict(os.environ, DISPLAY=display)
        rviz_log_path = os.path.join(tempfile.gettempdir(), "turtle_sim_ode_rviz.log")
        with open(rviz_log_path, "w") as rviz_log:
            rviz = subprocess.Popen(
                ["rviz", "-d", rospy.get_param("~rviz_config")],
                env=env,
                stdout=rviz_log,
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )
        shot_path = os.path.join(tempfile.gettempdir(), rospy.get_param("~screenshot", "turtle_sim_ode_rviz.png"))
        colour = rospy.get_param("~colour", "blue")
        try:
            deadline = time.monotonic() + rospy.get_param("~timeout")
            pixels, image, grab_error = 0, None, ""
            while time.monotonic() < deadline and pixels < rospy.get_param("~min_robot_pixels"):
                self.assertIsNone(xvfb.poll(), "Xvfb on %s exited with %s" % (display, xvfb.poll()))
                self.assertIsNone(
                    rviz.poll(), "rviz exited with %s; its output:\n%s" % (rviz.poll(), tail(rviz_log_path))
                )
                grab = subprocess.run(
                    ["xwd", "-root", "-silent", "-display", display], stdout=subprocess.PIPE, stderr=subprocess.PIPE
                )
                if grab.returncode == 0:
                    image = read_xwd(grab.stdout)
                    pixels = robot_pixels(image, colour)
                else:
                    # A grab can fail while rviz (re)creates its GL window: the next try decides.
                    grab_error = grab.stderr.decode(errors="replace").strip()
                    rospy.logwarn("xwd on %s failed [%s]: %s", display, grab.returncode, grab_error)
                time.sleep(1.0)  # rviz draws in its own time: nothing to wait on but the picture
            self.assertIsNotNone(
                image, "no screenshot of %s could be taken; last xwd error: %s" % (display, grab_error)
            )
            plt.imsave(shot_path, image)
            self.assertGreaterEqual(
                pixels,
                rospy.get_param("~min_robot_pixels"),
                "too few %s pixels in rviz; last screenshot: %s; rviz output:\n%s"
                % (colour, shot_path, tail(rviz_log_path)),
            )
        finally:
            stop(rviz)
            stop(xvfb)


if __name__ == "__main__":
    rospy.init_node("test_rviz_render")
    rostest.rosrun("turtle_sim_ode", "rviz_shows_robot", RvizShowsRobot, sys.argv)
