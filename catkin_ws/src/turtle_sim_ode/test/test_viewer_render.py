#!/usr/bin/env python3
"""rostest node: the viewer (what gzclient runs) under a test's own Xvfb, read from screenshots as a person reads
it. The world (viewer_arena.world, in turtlebot3_world's style) is running before the viewer starts: its blue walls
and yellow pillars show, seen top-down (the hexagon keeps its proportions); a red box spawned with
/gazebo/spawn_sdf_model shows where it stands among the walls, moves where set_model_state puts it (the world paused
meanwhile) and leaves when deleted; a Collada block shows the green its file gives. Screenshots are kept as PNG
files (~screenshot_dir) for people to look at."""
import math
import os
import subprocess
import sys
import tempfile
import time
import unittest
from typing import Callable, Optional, Tuple

import numpy as np
import rospy
import rostest
from gazebo_msgs.msg import ModelState
from geometry_msgs.msg import Point, Pose, Quaternion

from gazebo_clients import connect_gazebo_services
from workspace_testing.processes import stop_group
from workspace_testing.screen import start_xvfb
from workspace_testing.tool_window import save_png
from workspace_testing.xwd_image import read_xwd

# The arena (test/fixtures/tso_mesh_worlds/models/tso_viewer_arena): walls from x = -2.05 to 2.05 m (apothem 2 m
# plus half their thickness), drawn top-down with world x up the screen and world y to the left.
ARENA_X_EXTENT = 4.1
ARENA_Y_EXTENT = 4.72  # between the hexagon's corners on y, walls' thickness included
RED_BOX = """<sdf version="1.6"><model name="red_box"><static>true</static><link name="body">
  <visual name="look"><geometry><box><size>0.6 0.6 0.6</size></box></geometry>
    <material><ambient>1 0 0 1</ambient><diffuse>1 0 0 1</diffuse></material></visual>
  <collision name="shape"><geometry><box><size>0.6 0.6 0.6</size></box></geometry></collision>
</link></model></sdf>"""
GREEN_BLOCK = """<sdf version="1.6"><model name="green_block"><static>true</static><link name="body">
  <visual name="look"><geometry><mesh><uri>package://tso_mesh_worlds/meshes/green_block.dae</uri>
    <scale>1.5 1.5 1.5</scale></mesh></geometry></visual>
</link></model></sdf>"""

Mask = Callable[[np.ndarray], np.ndarray]


# Gazebo's background and ground plane (Gazebo/Grey) as the viewer draws them: the 3D view is where they fill most
# of the rows and columns (menus and the control window have a pixel of that grey here and there).
VIEW_GREY = (178, 178, 178)


def view_only(image: np.ndarray) -> np.ndarray:
    """The image with everything outside the 3D view blacked out."""
    grey = np.all(np.abs(image.astype(int) - VIEW_GREY) <= 3, axis=2)
    columns = np.nonzero(grey.sum(axis=0) > 0.5 * grey.sum(axis=0).max())[0]
    rows = np.nonzero(grey.sum(axis=1) > 0.5 * grey.sum(axis=1).max())[0]
    view = np.zeros_like(image)
    if len(columns) and len(rows):
        view[rows[0] : rows[-1] + 1, columns[0] : columns[-1] + 1] = image[
            rows[0] : rows[-1] + 1, columns[0] : columns[-1] + 1
        ]
    return view


def channels(image: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    view = view_only(image)
    return tuple(view[:, :, i].astype(int) for i in range(3))  # type: ignore[return-value]


def blue(image: np.ndarray) -> np.ndarray:
    r, g, b = channels(image)
    return (b > r + 60) & (b > g + 40)


def yellow(image: np.ndarray) -> np.ndarray:
    r, g, b = channels(image)
    return (r > b + 80) & (g > b + 80) & (abs(r - g) < 50)


def red(image: np.ndarray) -> np.ndarray:
    r, g, b = channels(image)
    return (r > g + 80) & (r > b + 80)


def green(image: np.ndarray) -> np.ndarray:
    r, g, b = channels(image)
    return (g > r + 60) & (g > b + 60)


def region(mask: np.ndarray) -> Optional[Tuple[float, float, int, int, int, int]]:
    """Centroid (x, y) and bounding box (x0, y0, x1, y1) of a mask's pixels; None if it has none."""
    ys, xs = np.nonzero(mask)
    if len(xs) == 0:
        return None
    return float(xs.mean()), float(ys.mean()), int(xs.min()), int(ys.min()), int(xs.max()), int(ys.max())


class ArenaView:
    """Where world points show, calibrated on the arena's walls as seen: their box's centre is the arena's centre,
    its height the walls' x extent."""

    def __init__(self, walls: Tuple[float, float, int, int, int, int]) -> None:
        _, _, x0, y0, x1, y1 = walls
        self.centre = ((x0 + x1) / 2, (y0 + y1) / 2)
        self.pixels_per_metre = (y1 - y0) / ARENA_X_EXTENT
        self.width, self.height = x1 - x0, y1 - y0

    def project(self, x: float, y: float) -> Tuple[float, float]:
        return self.centre[0] - y * self.pixels_per_metre, self.centre[1] - x * self.pixels_per_metre


class ViewerShowsTheWorld(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        connect_gazebo_services(cls, 120)

    def setUp(self) -> None:
        self.timeout = rospy.get_param("~timeout", 90.0)
        self.shots = rospy.get_param("~screenshot_dir", tempfile.gettempdir())
        self.xvfb, self.display = start_xvfb()
        self.log_path = os.path.join(tempfile.gettempdir(), "turtle_sim_ode_viewer.log")
        with open(self.log_path, "w") as log:
            self.viewer = subprocess.Popen(
                ["rosrun", "turtle_sim_ode", "viewer"],
                env=dict(os.environ, DISPLAY=self.display),
                stdout=log,
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )

    def tearDown(self) -> None:
        stop_group(self.viewer)
        stop_group(self.xvfb)

    def log_tail(self) -> str:
        with open(self.log_path, errors="replace") as log:
            return "".join(log.readlines()[-15:])

    def screenshot_until(self, name: str, shows: Callable[[np.ndarray], bool]) -> np.ndarray:
        """Screenshots until ``shows`` holds for one (or time runs out); the last is kept as NAME.png."""
        deadline = time.monotonic() + self.timeout
        image = None
        while True:
            self.assertIsNone(self.viewer.poll(), "the viewer exited; its output:\n" + self.log_tail())
            grab = subprocess.run(["xwd", "-root", "-silent", "-display", self.display], capture_output=True)
            if grab.returncode == 0:  # a grab can fail while rviz (re)creates its GL window: the next one decides
                image = read_xwd(grab.stdout)
                if shows(image) or time.monotonic() > deadline:
                    break
            elif time.monotonic() > deadline:
                break
            time.sleep(0.5)  # rviz draws in its own time: nothing to wait on but the picture
        self.assertIsNotNone(image, "no screenshot of %s could be taken" % self.display)
        save_png(image, os.path.join(self.shots, name + ".png"))
        return image

    def near(self, mask: Mask, view: ArenaView, x: float, y: float, tolerance_m: float) -> Callable[[np.ndarray], bool]:
        def shows(image: np.ndarray) -> bool:
            found = region(mask(image))
            if found is None or np.count_nonzero(mask(image)) < 50:
                return False
            want = view.project(x, y)
            return math.dist(found[:2], want) < tolerance_m * view.pixels_per_metre

        return shows

    def test_world_spawn_move_delete_mesh(self) -> None:
        arena = self.screenshot_until(
            "viewer_arena", lambda image: np.count_nonzero(blue(image)) > 2000 and np.count_nonzero(yellow(image)) > 200
        )
        walls = region(blue(arena))
        self.assertIsNotNone(walls, "no blue walls in the viewer; its output:\n" + self.log_tail())
        view = ArenaView(walls)  # type: ignore[arg-type]
        # Top-down: the hexagon keeps its proportions (a slanted view would flatten it).
        self.assertAlmostEqual(view.width / view.height, ARENA_Y_EXTENT / ARENA_X_EXTENT, delta=0.12)
        # The pillars stand where the world puts them among the walls.
        pillars = region(yellow(arena))
        self.assertLess(math.dist(pillars[:2], view.project(0.0, 0.0)), 0.3 * view.pixels_per_metre)  # type: ignore[index]
        self.assertEqual(np.count_nonzero(red(arena)), 0)

        answer = self.spawn_sdf_model(
            "red_box", RED_BOX, "", Pose(Point(1.2, 0.0, 0.3), Quaternion(0, 0, 0, 1)), "world"
        )
        self.assertTrue(answer.success, answer.status_message)
        shot = self.screenshot_until("viewer_red_box", self.near(red, view, 1.2, 0.0, 0.25))
        self.assertTrue(self.near(red, view, 1.2, 0.0, 0.25)(shot), "the spawned red box does not show where it stands")

        self.pause_physics()
        state = ModelState(model_name="red_box", pose=Pose(Point(-0.5, 1.2, 0.3), Quaternion(0, 0, 0, 1)))
        self.assertTrue(self.set_model_state(state).success)
        moved = self.screenshot_until("viewer_red_box_moved", self.near(red, view, -0.5, 1.2, 0.25))
        self.assertTrue(self.near(red, view, -0.5, 1.2, 0.25)(moved), "the red box did not move in the viewer")
        self.unpause_physics()

        self.assertTrue(self.delete_model("red_box").success)
        gone = self.screenshot_until("viewer_red_box_deleted", lambda image: np.count_nonzero(red(image)) == 0)
        self.assertEqual(np.count_nonzero(red(gone)), 0, "the deleted red box still shows")

        answer = self.spawn_sdf_model(
            "green_block", GREEN_BLOCK, "", Pose(Point(-1.0, -0.8, 0.0), Quaternion(0, 0, 0, 1)), "world"
        )
        self.assertTrue(answer.success, answer.status_message)
        block = self.screenshot_until("viewer_collada_block", self.near(green, view, -1.0, -0.8, 0.3))
        self.assertTrue(self.near(green, view, -1.0, -0.8, 0.3)(block), "the Collada block's own green does not show")
        self.delete_model("green_block")


if __name__ == "__main__":
    rospy.init_node("test_viewer_render")
    rostest.rosrun("turtle_sim_ode", "viewer_shows_the_world", ViewerShowsTheWorld, sys.argv)
