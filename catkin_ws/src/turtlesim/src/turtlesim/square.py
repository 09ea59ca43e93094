"""draw_square: drive 2 m, stop, turn a quarter turn left, stop, and again (twin of src/square_driver.cpp and
src/draw_square.cpp). SquareDriver has no ROS in it."""
from __future__ import annotations

import math
from typing import List, NamedTuple, Tuple

from turtlesim.world import wrap_angle

SIDE = 2.0  # m
LINEAR_SPEED = 1.0  # m/s
ANGULAR_SPEED = 0.4  # rad/s
POSITION_TOLERANCE = 0.1  # m
ANGLE_TOLERANCE = 0.01  # rad
STOPPED_VELOCITY = 0.0001  # m/s and rad/s
TICK = 0.016  # s between two commands

FORWARD, STOP_FORWARD, TURN, STOP_TURN = "forward", "stop_forward", "turn", "stop_turn"


class SquarePose(NamedTuple):
    x: float
    y: float
    theta: float
    linear_velocity: float
    angular_velocity: float


class SquareDriver:
    def __init__(self):
        self.state = FORWARD
        self.goal = SquarePose(0.0, 0.0, 0.0, 0.0, 0.0)
        self._started = False

    def _reached(self, pose: SquarePose) -> bool:
        return (
            abs(pose.x - self.goal.x) < POSITION_TOLERANCE
            and abs(pose.y - self.goal.y) < POSITION_TOLERANCE
            and abs(wrap_angle(pose.theta - self.goal.theta)) < ANGLE_TOLERANCE
        )

    def _set_goal(self, x: float, y: float, theta: float, log: List[str]) -> None:
        self.goal = SquarePose(x, y, wrap_angle(theta), 0.0, 0.0)
        log.append("New goal [%f %f, %f]" % (self.goal.x, self.goal.y, self.goal.theta))

    def _goal_ahead(self, pose: SquarePose, log: List[str]) -> None:
        self._set_goal(pose.x + SIDE * math.cos(pose.theta), pose.y + SIDE * math.sin(pose.theta), pose.theta, log)

    def step(self, pose: SquarePose, log: List[str]) -> Tuple[float, float]:
        """(linear, angular) for one tick given the latest pose; lines worth logging are appended to `log`."""
        stopped = pose.linear_velocity < STOPPED_VELOCITY and abs(pose.angular_velocity) < STOPPED_VELOCITY
        if not self._started:
            self._started = True
            self.state = FORWARD
            self._goal_ahead(pose, log)
        if self.state in (FORWARD, TURN):
            if self._reached(pose):
                self.state = STOP_FORWARD if self.state == FORWARD else STOP_TURN
                return 0.0, 0.0
            return (LINEAR_SPEED, 0.0) if self.state == FORWARD else (0.0, ANGULAR_SPEED)
        if stopped:
            log.append("Reached goal")
            if self.state == STOP_FORWARD:
                self.state = TURN
                self._set_goal(pose.x, pose.y, pose.theta + math.pi / 2.0, log)
            else:
                self.state = FORWARD
                self._goal_ahead(pose, log)
        return 0.0, 0.0


def main() -> int:
    import rospy
    from geometry_msgs.msg import Twist
    from std_srvs.srv import Empty

    from turtlesim.msg import Pose

    rospy.init_node("draw_square")
    reset = rospy.ServiceProxy("reset", Empty)
    try:
        reset.wait_for_service(30.0)
        reset()
    except (rospy.ROSException, rospy.ServiceException) as error:
        rospy.logfatal("Service [%s] did not answer (%s): is turtlesim_node running?", reset.resolved_name, error)
        return 1
    latest = {}  # "pose": the last turtle1/pose
    driver = SquareDriver()
    pub = rospy.Publisher("turtle1/cmd_vel", Twist, queue_size=1)
    rospy.Subscriber("turtle1/pose", Pose, lambda pose: latest.__setitem__("pose", pose), queue_size=1)

    def on_tick(_event) -> None:
        p = latest.get("pose")
        if p is None:
            return
        log = []
        twist = Twist()
        twist.linear.x, twist.angular.z = driver.step(
            SquarePose(p.x, p.y, p.theta, p.linear_velocity, p.angular_velocity), log
        )
        for line in log:
            rospy.loginfo(line)
        pub.publish(twist)

    rospy.Timer(rospy.Duration(TICK), on_tick)
    rospy.spin()
    return 0
