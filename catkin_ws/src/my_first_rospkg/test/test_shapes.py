#!/usr/bin/env python3
"""rostest node: the shape a node under test (~shape: circle, square, spiral, bounce) drives, measured on the
simulator's ground truth with sim time. Tolerances come from private params."""
import math
import sys
import unittest

import rospy
import rostest

from sim_recording import Recorder, fit_circle, straight_runs, unwrapped_yaw


class ShapeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.recorder = Recorder()

    def test_shape(self):
        getattr(self, "check_" + rospy.get_param("~shape"))()

    def check_circle(self):
        samples = self.recorder.wait_until_finished()
        radius = rospy.get_param("~radius")
        cx, cy, measured = fit_circle(samples)
        turned = unwrapped_yaw(samples)[-1] - samples[0].yaw
        rospy.loginfo(
            "circle: measured radius [%.4f] m for [%.3f] (error %.2f %%), turned [%.2f] rad",
            measured,
            radius,
            100 * abs(measured - radius) / radius,
            turned,
        )
        self.assertAlmostEqual(measured, radius, delta=rospy.get_param("~relative_tolerance") * radius)
        self.assertGreater(turned, 2 * math.pi * 0.95, "less than a lap")

    def check_square(self):
        samples = self.recorder.wait_until_finished()
        start, end = samples[0], samples[-1]
        closing = math.hypot(end.x - start.x, end.y - start.y)
        runs = straight_runs(samples)
        directions = [math.atan2(r[-1].y - r[0].y, r[-1].x - r[0].x) for r in runs]
        corners = [
            math.degrees(math.atan2(math.sin(b - a), math.cos(b - a))) for a, b in zip(directions, directions[1:])
        ]
        rospy.loginfo(
            "square: closing error [%.4f] m, corners %s deg, sides %s m",
            closing,
            ["%.2f" % c for c in corners],
            ["%.3f" % math.hypot(r[-1].x - r[0].x, r[-1].y - r[0].y) for r in runs],
        )
        self.assertEqual(len(runs), 4, "expected four straight sides")
        self.assertLess(closing, rospy.get_param("~closing_tolerance"))
        for corner in corners:
            self.assertAlmostEqual(corner, 90.0, delta=rospy.get_param("~corner_tolerance_deg"))

    def check_spiral(self):
        samples = self.recorder.wait_until_finished()
        a = rospy.get_param("~initial_radius")
        start = samples[0]
        # the centre of curvature at the start; at every quarter turn the robot is further away from it
        cx, cy = start.x - a * math.sin(start.yaw), start.y + a * math.cos(start.yaw)
        yaws = unwrapped_yaw(samples)
        radii, next_mark = [], 0.0
        for sample, yaw in zip(samples, yaws):
            if yaw - start.yaw >= next_mark:
                radii.append(math.hypot(sample.x - cx, sample.y - cy))
                next_mark += math.pi / 2
        rospy.loginfo("spiral: radius at each quarter turn %s", ["%.3f" % r for r in radii])
        self.assertGreaterEqual(len(radii), rospy.get_param("~min_quarter_turns"))
        for inner, outer in zip(radii, radii[1:]):
            self.assertGreater(outer, inner)

    def check_bounce(self):
        duration = rospy.get_param("~duration")
        samples = self.recorder.record_for(duration)
        limit = rospy.get_param("~limit")
        worst = max(max(abs(s.x), abs(s.y)) for s in samples)
        span = max(s.x for s in samples) - min(s.x for s in samples)
        rospy.loginfo(
            "bounce: [%.1f] s, largest |x|,|y| [%.3f] m, x span [%.3f] m", samples[-1].t - samples[0].t, worst, span
        )
        self.assertLessEqual(worst, limit)
        self.assertGreater(span, 3.5, "the robot did not go back and forth")


if __name__ == "__main__":
    rospy.init_node("test_shapes")
    rostest.rosrun("my_first_rospkg", "shapes", ShapeTest, sys.argv)
