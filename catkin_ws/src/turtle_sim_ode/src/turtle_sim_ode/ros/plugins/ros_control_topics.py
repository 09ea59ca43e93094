"""The topics and the action of one simulated ros_control controller: plain values from control.* to messages and
back, with the message types the real controllers use."""
from __future__ import annotations

import math
import threading
from typing import Any, Callable, Dict, List, Optional, Tuple

import actionlib
import rospy
from control_msgs.msg import (
    FollowJointTrajectoryAction,
    FollowJointTrajectoryFeedback,
    FollowJointTrajectoryResult,
    GripperCommandAction,
    GripperCommandResult,
    JointControllerState,
    JointTrajectoryControllerState,
)
from geometry_msgs.msg import TransformStamped, Twist, TwistStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64, Float64MultiArray
from tf2_msgs.msg import TFMessage
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from turtle_sim_ode.control.controller import Controller
from turtle_sim_ode.control.gripper import GripperActionController
from turtle_sim_ode.control.trajectory import SUCCESSFUL, JointTrajectoryController, Point, TrajectoryGoal
from turtle_sim_ode.ros.periodic import publisher, sim_stamp, subscriber

INPUT_TYPES = {
    "float64": Float64,
    "float64_array": Float64MultiArray,
    "twist": Twist,
    "joint_trajectory": JointTrajectory,
}
# The controllers with an action server: its name, action type and result type.
ACTIONS = {
    JointTrajectoryController: ("follow_joint_trajectory", FollowJointTrajectoryAction, FollowJointTrajectoryResult),
    GripperActionController: ("gripper_cmd", GripperCommandAction, GripperCommandResult),
}
OUTPUT_TYPES = {
    "joint_controller_state": JointControllerState,
    "joint_states": JointState,
    "odometry": Odometry,
    "tf": TFMessage,
    "joint_trajectory_state": JointTrajectoryControllerState,
    "twist_stamped": TwistStamped,
}


def trajectory_request(request: Any, goal_id: str) -> TrajectoryGoal:
    """A follow_joint_trajectory goal with its tolerances."""
    goal = trajectory_goal(request.trajectory, goal_id)
    goal.path_tolerance = {t.name: (t.position, t.velocity, t.acceleration) for t in request.path_tolerance}
    goal.goal_tolerance = {t.name: (t.position, t.velocity, t.acceleration) for t in request.goal_tolerance}
    goal.goal_time_tolerance = request.goal_time_tolerance.to_sec()
    return goal


def trajectory_goal(msg: JointTrajectory, goal_id: Optional[str] = None) -> TrajectoryGoal:
    points = [
        Point(list(p.positions), list(p.velocities), list(p.accelerations), p.time_from_start.to_sec())
        for p in msg.points
    ]
    return TrajectoryGoal(list(msg.joint_names), points, msg.header.stamp.to_sec(), goal_id=goal_id)


def plain_input(kind: str, msg: Any) -> Any:
    if kind == "float64":
        return msg.data
    if kind == "float64_array":
        return list(msg.data)
    if kind == "twist":
        return (msg.linear.x, msg.angular.z)
    return trajectory_goal(msg)


def _yaw_quaternion(yaw: float) -> Tuple[float, float, float, float]:
    return (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))


def _diagonal(values: List[float]) -> List[float]:
    return [values[i] if i == j else 0.0 for i in range(6) for j in range(6)]


def _point(values: List[Tuple[float, float, float]]) -> JointTrajectoryPoint:
    return JointTrajectoryPoint(
        positions=[v[0] for v in values], velocities=[v[1] for v in values], accelerations=[v[2] for v in values]
    )


def message(kind: str, data: dict) -> Any:
    """The message of an outgoing payload (control.* field names)."""
    stamp = sim_stamp(data["stamp"])
    if kind == "joint_controller_state":
        msg = JointControllerState(**{k: v for k, v in data.items() if k != "stamp"})
    elif kind == "joint_states":
        msg = JointState(name=data["name"], position=data["position"], velocity=data["velocity"], effort=data["effort"])
    elif kind == "odometry":
        msg = Odometry(child_frame_id=data["child_frame_id"])
        msg.header.frame_id = data["frame_id"]
        msg.pose.pose.position.x, msg.pose.pose.position.y = data["x"], data["y"]
        q = msg.pose.pose.orientation
        q.x, q.y, q.z, q.w = _yaw_quaternion(data["yaw"])
        msg.twist.twist.linear.x, msg.twist.twist.angular.z = data["linear"], data["angular"]
        msg.pose.covariance = _diagonal(data["pose_covariance"])
        msg.twist.covariance = _diagonal(data["twist_covariance"])
    elif kind == "tf":
        transform = TransformStamped(child_frame_id=data["child_frame_id"])
        transform.header.frame_id, transform.header.stamp = data["frame_id"], stamp
        transform.transform.translation.x, transform.transform.translation.y = data["x"], data["y"]
        r = transform.transform.rotation
        r.x, r.y, r.z, r.w = _yaw_quaternion(data["yaw"])
        return TFMessage(transforms=[transform])
    elif kind == "joint_trajectory_state":
        msg = JointTrajectoryControllerState(joint_names=data["joint_names"])
        msg.desired, msg.actual, msg.error = (_point(data[k]) for k in ("desired", "actual", "error"))
    else:  # twist_stamped
        msg = TwistStamped()
        msg.twist.linear.x, msg.twist.angular.z = data["linear"], data["angular"]
    msg.header.stamp = stamp
    return msg


def topic_name(namespace: str, controller: str, topic: str) -> str:
    """control.controller's topic convention: relative to the controller, '@' to the robot, '/' absolute."""
    if topic.startswith("/"):
        return topic
    base = namespace.rstrip("/")
    return f"{base}/{topic[1:]}" if topic.startswith("@") else f"{base}/{controller}/{topic}"


class ControllerTopics:
    """The subscribers, publishers and (for a trajectory controller) follow_joint_trajectory action server of one
    loaded controller. Callbacks take ``lock`` (the controller manager's) before touching the controller."""

    def __init__(self, namespace: str, name: str, controller: Controller, lock: threading.Lock) -> None:
        self.namespace, self.name, self.controller, self.lock = namespace, name, controller, lock
        self.publishers = {
            # an absolute topic (/tf) is shared with the node's own synchronous publisher: no queue to impose on it
            topic: publisher(topic_name(namespace, name, topic), OUTPUT_TYPES[kind], None if topic[0] == "/" else 10)
            for topic, kind in controller.outputs.items()
        }
        self.subscribers = [
            subscriber(topic_name(namespace, name, topic), INPUT_TYPES[kind], self._callback(kind, handler), 1)
            for topic, (kind, handler) in controller.inputs.items()
        ]
        self.goals: Dict[str, Any] = {}
        self.action: Optional[actionlib.ActionServer] = None
        action = ACTIONS.get(type(controller))
        if action is not None:
            action_name, action_type, self.result_type = action
            self.action = actionlib.ActionServer(
                topic_name(namespace, name, action_name), action_type, self._on_goal, self._on_cancel, auto_start=False
            )
            self.action.start()

    def _callback(self, kind: str, handler: Callable[[Any], None]) -> Callable[[Any], None]:
        def on_message(msg: Any) -> None:
            value = plain_input(kind, msg)
            with self.lock:
                if not self.controller.running:
                    rospy.logerr_throttle(1.0, f"{self.name}: Can't accept new commands. Controller is not running.")
                    return
                handler(value)

        return on_message

    def _on_goal(self, handle: Any) -> None:
        """actionlib calls this holding its own lock: the manager's lock is taken inside it, never the reverse."""
        goal_id, request = handle.get_goal_id().id, handle.get_goal()
        with self.lock:
            if isinstance(self.controller, JointTrajectoryController):
                code, text = self.controller.submit(trajectory_request(request, goal_id))
                accepted, rejection = code == SUCCESSFUL, {"error_code": code, "error_string": text}
            else:
                accepted, text = self.controller.submit(goal_id, request.command.position, request.command.max_effort)
                rejection = {}
            if accepted:
                self.goals[goal_id] = handle
            finished = self._take_results()
        if not accepted:
            rospy.logerr(f"{self.name}: {text}")
            handle.set_rejected(self.result_type(**rejection), text)
            return
        handle.set_accepted()
        self._settle(finished)

    def _on_cancel(self, handle: Any) -> None:
        goal_id = handle.get_goal_id().id
        with self.lock:
            if isinstance(self.controller, JointTrajectoryController):
                active = self.controller.active
                if active is not None and active.goal_id == goal_id:
                    self.controller.submit(TrajectoryGoal(self.controller.names, []))  # hold where it is
            else:
                self.controller.cancel(goal_id)
            finished = self._take_results()
        self._settle(finished)

    def _take_results(self) -> List[Tuple[Any, str, dict]]:
        """The goals the controller finished, with their handles (lock held)."""
        results = getattr(self.controller, "results", None)
        if not results:
            return []
        finished = [(self.goals.pop(goal_id, None), status, fields) for goal_id, status, fields in results]
        results.clear()
        return [entry for entry in finished if entry[0] is not None]

    def _settle(self, finished: List[Tuple[Any, str, dict]]) -> None:
        """Report finished goals to their clients (lock not held: actionlib takes its own)."""
        for handle, status, fields in finished:
            result, text = self.result_type(**fields), fields.get("error_string", "")
            if status == "succeeded":
                handle.set_succeeded(result, text)
            elif status == "aborted":
                rospy.logerr(f"{self.name}: goal aborted {text or fields}")
                handle.set_aborted(result, text)
            else:
                handle.set_canceled(result, text)

    def take(self) -> Tuple[list, list, list, list]:
        """What the last update left to send: outgoing payloads, errors to log, feedback of running goals with
        their handles, finished goals (lock held)."""
        errors = list(getattr(self.controller, "errors", []))
        if errors:
            self.controller.errors.clear()
        feedback = getattr(self.controller, "feedback", None) or []
        to_clients = [(self.goals[goal_id], state) for goal_id, state in feedback if goal_id in self.goals]
        if feedback:
            feedback.clear()
        return self.controller.drain(), errors, to_clients, self._take_results()

    def send(self, taken: Tuple[list, list, list, list]) -> None:
        """Publish and report what ``take`` gave (lock not held)."""
        outgoing, errors, to_clients, finished = taken
        for topic, kind, data in outgoing:
            self.publishers[topic].publish(message(kind, data))
        for handle, state in to_clients:
            point = message("joint_trajectory_state", state)
            handle.publish_feedback(
                FollowJointTrajectoryFeedback(
                    header=point.header,
                    joint_names=point.joint_names,
                    desired=point.desired,
                    actual=point.actual,
                    error=point.error,
                )
            )
        for error in errors:
            rospy.logerr_throttle(1.0, f"{self.name}: {error}")
        self._settle(finished)

    def close(self) -> None:
        for handle in list(self.goals.values()):
            handle.set_aborted(self.result_type(), "Controller unloaded")
        for sub in self.subscribers:
            sub.unregister()
        for pub in self.publishers.values():
            pub.unregister()
        if self.action is not None:  # actionlib has no shutdown: its topics go with their handles
            for handle in (self.action.goal_sub, self.action.cancel_sub):
                handle.unregister()
            for handle in (self.action.status_pub, self.action.result_pub, self.action.feedback_pub):
                handle.unregister()
            if getattr(self.action, "status_timer", None) is not None:
                self.action.status_timer.shutdown()
