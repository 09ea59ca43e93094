#!/usr/bin/env python3
"""Issue #31's acceptance, through ROS: the SMB as the course launches it drives on /cmd_vel through twist_mux and
diff_drive_controller (2 m in 4 s at 0.5 m/s), steers while it drives (its yaw rate between
scrub_margin / separation_multiplier and 1 of the command: diff_drive_controller's kinematics and the SMB's
skid, see turtle_sim_ode's test_skid_steer_turning.py), its wheels run DefaultRobotHWSim's PID (efforts
reported), and the EKF's odometry/filtered follows the ground truth."""
import math
import threading
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState

WAIT = 150.0  # s of wall time for the simulator, the spawn and the first messages on a loaded machine
WHEELS = ("LF_WHEEL_JOINT", "RF_WHEEL_JOINT", "LH_WHEEL_JOINT", "RH_WHEEL_JOINT")


def yaw_of(q):
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def wrapped(angle):
    return (angle + math.pi) % (2 * math.pi) - math.pi


class SmbControl(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # the controller manager at the root: <robotNamespace></robotNamespace> is the root namespace
        rospy.wait_for_service("/controller_manager/list_controllers", WAIT)
        listing = rospy.ServiceProxy("/controller_manager/list_controllers", ListControllers)
        while {c.name for c in listing().controller if c.state == "running"} != {
            "smb_joint_publisher",
            "smb_velocity_controller",
        }:
            rospy.sleep(0.1)  # sim time; the test's time-limit bounds it
        rospy.wait_for_service("/gazebo/get_model_state", WAIT)
        cls.model_state = rospy.ServiceProxy("/gazebo/get_model_state", GetModelState)
        while rospy.get_time() < rospy.get_param("~settled_after"):
            rospy.sleep(0.1)  # sim time: spawn_model drops the robot from 0.4 m
        cls.commands = rospy.Publisher("/cmd_vel", Twist, queue_size=1)
        cls.efforts = []
        rospy.Subscriber("/joint_states", JointState, cls.record_efforts)
        cls.filtered = None
        cls.filtered_changed = threading.Condition()
        rospy.Subscriber("/odometry/filtered", Odometry, cls.record_filtered)

    @classmethod
    def record_efforts(cls, states):
        named = dict(zip(states.name, states.effort))
        cls.efforts.append([named.get(wheel, 0.0) for wheel in WHEELS])

    @classmethod
    def record_filtered(cls, odometry):
        with cls.filtered_changed:
            cls.filtered = odometry
            cls.filtered_changed.notify_all()

    def pose(self):
        state = self.model_state("smb", "world")
        self.assertTrue(state.success, state.status_message)
        return state.pose.position, yaw_of(state.pose.orientation)

    def drive(self, linear, angular):
        """/cmd_vel at 10 Hz (as teleop_twist_keyboard repeats) for drive_time of sim time: the ground truth's
        (distance, yaw change) when the commands end, and from rest to rest the ground truth's and the EKF's (compared
        at rest, with estimates stamped after the robot was seen at rest, where the filter's latency does not
        count)."""
        start, start_yaw = self.pose()
        filtered_start = self.filtered_after(rospy.get_time())
        rate = rospy.Rate(10)
        end_time = rospy.get_time() + rospy.get_param("~drive_time")
        while rospy.get_time() < end_time:
            self.commands.publish(Twist(linear=Vector3(linear, 0, 0), angular=Vector3(0, 0, angular)))
            rate.sleep()
        end, end_yaw = self.pose()
        driven = (math.hypot(end.x - start.x, end.y - start.y), wrapped(end_yaw - start_yaw))
        self.commands.publish(Twist())
        state = self.model_state("smb", "world")
        while math.hypot(state.twist.linear.x, state.twist.linear.y, state.twist.angular.z) > 0.01:
            rospy.sleep(0.1)  # sim time; the test's time-limit bounds it
            state = self.model_state("smb", "world")
        rest, rest_yaw = self.pose()
        truth = (math.hypot(rest.x - start.x, rest.y - start.y), wrapped(rest_yaw - start_yaw))
        filtered_end = self.filtered_after(rospy.get_time())
        estimate = (
            math.hypot(
                filtered_end.position.x - filtered_start.position.x,
                filtered_end.position.y - filtered_start.position.y,
            ),
            wrapped(yaw_of(filtered_end.orientation) - yaw_of(filtered_start.orientation)),
        )
        rospy.loginfo(
            "cmd (%.2f, %.2f): driven %.3f m, %.3f rad; at rest %.3f m, %.3f rad; odometry/filtered %.3f m, %.3f rad"
            % ((linear, angular) + driven + truth + estimate)
        )
        self.assert_ekf_follows(truth, estimate)
        return driven

    def filtered_after(self, time):
        """The EKF's pose from the first odometry/filtered stamped after ``time`` (sim time). The filter stamps its
        output with its last fused measurement (robot_localization's ros_filter.cpp, as our drop-in): on a loaded
        machine it runs behind the simulator, and the next message it publishes may still lack the end of the drive
        (or hold the end of the one before)."""
        with self.filtered_changed:
            arrived = self.filtered_changed.wait_for(
                lambda: self.filtered is not None and self.filtered.header.stamp.to_sec() > time, WAIT
            )
            self.assertTrue(arrived, "no odometry/filtered stamped after %.3f s within %g s" % (time, WAIT))
            return self.filtered.pose.pose

    def assert_ekf_follows(self, truth, estimate):
        self.assertAlmostEqual(estimate[0], truth[0], delta=rospy.get_param("~ekf_tolerance") * truth[0])
        self.assertAlmostEqual(estimate[1], truth[1], delta=rospy.get_param("~ekf_yaw_tolerance"))

    def test_1_drives_2_m_in_4_s(self):
        speed, seconds = rospy.get_param("~speed"), rospy.get_param("~drive_time")
        distance, yaw = self.drive(speed, 0.0)
        self.assertAlmostEqual(distance, speed * seconds, delta=rospy.get_param("~distance_tolerance"))
        self.assertLess(abs(yaw), 0.05)
        strongest = max(abs(effort) for sample in self.efforts for effort in sample)
        self.assertGreater(strongest, 1.0, "no wheel effort reported: velocity motors, not the pid_gains' PID")

    def test_2_turns_while_driving(self):
        speed, turn = rospy.get_param("~speed"), rospy.get_param("~turn")
        commanded = turn * rospy.get_param("~drive_time")
        distance, yaw = self.drive(speed, turn)
        lowest = rospy.get_param("~scrub_margin") * commanded / rospy.get_param("~separation_multiplier")
        self.assertGreater(yaw, lowest, "the SMB turned %.3f rad of %.3f commanded" % (yaw, commanded))
        self.assertLess(yaw, commanded)
        self.assertGreater(distance, 0.5 * speed * rospy.get_param("~drive_time"))


if __name__ == "__main__":
    rospy.init_node("test_smb_control")
    rostest.rosrun("turtle_sim_ode_smb", "smb_control", SmbControl)
