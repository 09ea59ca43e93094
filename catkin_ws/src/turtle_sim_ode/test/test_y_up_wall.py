#!/usr/bin/env python3
"""rostest node (issue #22): `roslaunch tso_mesh_worlds y_up_wall_world.launch x_pos:=...`, written the way
turtlebot3_gazebo writes turtlebot3_world.launch, puts the world's Y_UP Collada wall where Gazebo puts it: the
robot's laser sees it at the distance Gazebo's loader gives, and driven into it the robot stops at its near face."""
import math
import sys
import time
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ModelStates
from geometry_msgs.msg import Twist, Vector3
from sensor_msgs.msg import LaserScan
from workspace_testing.processes import LoggedProcess

MODEL = "sim_fixture_bot"
# Where Gazebo puts the wall. gazebo-classic gazebo/common/ColladaLoader.cc, ColladaLoader::Load scales the mesh by
# <unit meter="0.0254"> and applies the node's <translate>0.5 0 0</translate> (in file units); it never reads
# <up_axis>Y_UP</up_axis>, so the file's Z stays up. The file's box (test/fixtures/make_meshes.py, WALL_INCHES) runs
# x 40..44, y -20..20, z 0..12 in: its near face lies (40 + 0.5) * 0.0254 = 1.0287 m along the model's x, 0.508 m
# to either side, 0.3048 m high. y_up_wall.world includes the model at x = 1.0: the near face is at world x 2.0287.
WALL_NEAR_FACE_X = 1.0 + (40.0 + 0.5) * 0.0254
WALL_HALF_WIDTH = 20.0 * 0.0254
# The robot (gazebo_ros/test/fixture_packages/sim_fixture_description/urdf/robot.urdf.xacro): scan_link 0.02 m
# behind the model's origin and 0.132 m up (below the wall's top); the body box, 0.16 m long centred 0.03 m behind
# the origin, reaches 0.05 m ahead of it: the robot's front radius.
SCAN_X_OFFSET = -0.02
FRONT_REACH = -0.03 + 0.16 / 2
# Had the loader turned the Y_UP file upright (the old fault), the wall would lie across y -0.3048..0, so the beams
# at positive angles (left of the robot's heading) would miss it.
BEAM_HALF_FAN = 0.2  # rad: beams at |angle| <= this meet the near face (1.55 m * tan 0.2 = 0.31 m < 0.508 m)
RANGE_TOLERANCE = 0.03  # m: gazebo_ros_laser's <resolution> 0.01 plus the robot settling on its wheels
PENETRATION_TOLERANCE = 0.02  # m: ODE's contact surface layer and soft contacts


class YUpWall(unittest.TestCase):
    launch = None

    @classmethod
    def setUpClass(cls) -> None:
        cls.spawn_x = float(rospy.get_param("~spawn_x"))
        command = ["roslaunch", "tso_mesh_worlds", "y_up_wall_world.launch", "x_pos:=%g" % cls.spawn_x]
        cls.launch = LoggedProcess(command)
        rospy.on_shutdown(cls.launch.stop)  # rostest's time-limit signal must not leave the launch behind
        cls.states = None
        cls.driven_x = None  # the robot's x from each /gazebo/model_states while test_b drives
        rospy.Subscriber("/gazebo/model_states", ModelStates, cls.on_states, queue_size=10)

    @classmethod
    def on_states(cls, message: ModelStates) -> None:
        cls.states = message
        if cls.driven_x is not None and MODEL in message.name:
            cls.driven_x.append(message.pose[message.name.index(MODEL)].position.x)

    @classmethod
    def tearDownClass(cls) -> None:
        cls.launch.close()

    def robot_x(self) -> float:
        """The robot's ground-truth x from /gazebo/model_states, once the launch file's spawn_model has spawned it."""
        deadline = time.monotonic() + float(rospy.get_param("~startup_timeout"))
        while self.states is None or MODEL not in self.states.name:
            self.assertIsNone(self.launch.process.poll(), "roslaunch ended:\n" + self.launch.output())
            self.assertLess(time.monotonic(), deadline, "robot never spawned:\n" + self.launch.output())
            time.sleep(0.1)  # wall time: sim time may not run yet
        return self.states.pose[self.states.name.index(MODEL)].position.x

    def test_a_laser_sees_the_wall_where_gazebo_puts_it(self) -> None:
        self.assertAlmostEqual(self.robot_x(), self.spawn_x, delta=0.01)
        rospy.sleep(1.0)  # sim time: the robot settles on its wheels, later scans see the world with it in
        scan = rospy.wait_for_message("/scan", LaserScan, timeout=30)
        scan_x = self.robot_x() + SCAN_X_OFFSET
        checked = 0
        for index, measured in enumerate(scan.ranges):
            angle = scan.angle_min + index * scan.angle_increment
            if abs(angle) <= BEAM_HALF_FAN:
                expected = (WALL_NEAR_FACE_X - scan_x) / math.cos(angle)
                self.assertLess(abs(math.tan(angle) * (WALL_NEAR_FACE_X - scan_x)), WALL_HALF_WIDTH)
                self.assertAlmostEqual(measured, expected, delta=RANGE_TOLERANCE, msg="beam at %.3f rad" % angle)
                checked += 1
        centre = round(-scan.angle_min / scan.angle_increment)
        rospy.loginfo(
            "scan from x %.4f: beam at %.4f rad %.4f m, the wall's near face %.4f m ahead",
            scan_x,
            scan.angle_min + centre * scan.angle_increment,
            scan.ranges[centre],
            WALL_NEAR_FACE_X - scan_x,
        )
        self.assertGreaterEqual(checked, 10, "beams in +-%g rad: %d" % (BEAM_HALF_FAN, checked))

    def test_b_driven_into_the_wall_it_stops_at_the_near_face(self) -> None:
        start_x = self.robot_x()
        stop_line = WALL_NEAR_FACE_X - FRONT_REACH
        speed, drive_time = 0.25, 10.0  # 2.5 m commanded, the wall is about 1.5 m ahead
        self.assertGreater(start_x + speed * drive_time, stop_line + 0.5)
        type(self).driven_x = []
        cmd = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
        rate = rospy.Rate(10)  # sim time (/use_sim_time set by the .test)
        for _ in range(int(drive_time * 10)):
            cmd.publish(Twist(linear=Vector3(speed, 0, 0)))
            rate.sleep()
        cmd.publish(Twist())
        driven = list(self.driven_x)
        rospy.loginfo("drive: max x %.4f, last x %.4f, stop line %.4f", max(driven), driven[-1], stop_line)
        self.assertGreater(len(driven), 50, "model_states while driving")
        self.assertLessEqual(max(driven), stop_line + PENETRATION_TOLERANCE, "passed the wall's near face")
        self.assertGreater(driven[-1], stop_line - 0.05, "never reached the wall (%.3f m)" % driven[-1])


if __name__ == "__main__":
    rospy.init_node("test_y_up_wall")
    rostest.rosrun("turtle_sim_ode", "y_up_wall", YUpWall, sys.argv)
