"""turtlesim_node's ROS interface: the world services, each turtle's topics and services, the background params
and the 16 ms update loop on wall time. The window (window.py) only reads what this class holds."""
from __future__ import annotations

import threading
import time
from typing import Dict, List, Tuple

import rospy
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty, EmptyResponse

from turtlesim.msg import Color, Pose
from turtlesim.srv import (
    Kill,
    KillResponse,
    SetPen,
    SetPenResponse,
    Spawn,
    SpawnResponse,
    TeleportAbsolute,
    TeleportAbsoluteResponse,
    TeleportRelative,
    TeleportRelativeResponse,
)
from turtlesim.world import DEFAULT_BACKGROUND, UPDATE_PERIOD, WORLD_SIZE, Rgb, World, WorldError

BACKGROUND_PARAMS = ("~background_r", "~background_g", "~background_b")
WALL_WARNING_PERIOD = 1.0  # s between two wall warnings of the same turtle
WARNING_PERIOD = 1.0  # s between two warnings of one kind: ignored commands, failed updates
MAX_LAG = 0.25  # s: a loop further behind than this skips the missed updates instead of catching up


class TurtleHandles:
    """One turtle's publishers, subscriber and services, under the turtle's name."""

    def __init__(self, node: "TurtlesimNode", name: str):
        self.pose_pub = rospy.Publisher(name + "/pose", Pose, queue_size=1)
        self.colour_pub = rospy.Publisher(name + "/color_sensor", Color, queue_size=1)
        self.cmd_sub = rospy.Subscriber(name + "/cmd_vel", Twist, node.on_cmd_vel, callback_args=name, queue_size=1)
        self.services = [
            rospy.Service(name + "/set_pen", SetPen, lambda req: node.on_set_pen(name, req)),
            rospy.Service(
                name + "/teleport_absolute", TeleportAbsolute, lambda req: node.on_teleport_absolute(name, req)
            ),
            rospy.Service(
                name + "/teleport_relative", TeleportRelative, lambda req: node.on_teleport_relative(name, req)
            ),
        ]
        self.last_wall_warning = float("-inf")

    def close(self) -> None:
        for service in self.services:
            service.shutdown("turtle killed")
        self.cmd_sub.unregister()
        self.pose_pub.unregister()
        self.colour_pub.unregister()


def read_background() -> Rgb:
    """The ~background_r/_g/_b params; rospy.ServiceException naming the param if one is not an int in 0..255."""
    colour = []
    for name, default in zip(BACKGROUND_PARAMS, DEFAULT_BACKGROUND):
        value = rospy.get_param(name, default)
        if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 255:
            raise rospy.ServiceException(
                "Parameter [%s] must be an integer in [0, 255], got [%r]" % (rospy.resolve_name(name), value)
            )
        colour.append(value)
    return tuple(colour)


class TurtlesimNode:
    def __init__(self):
        for name, default in zip(BACKGROUND_PARAMS, DEFAULT_BACKGROUND):
            if not rospy.has_param(name):
                rospy.set_param(name, default)
        self.lock = threading.RLock()  # guards world and handles: ROS callbacks, the update loop and the window
        self.world = World(read_background())  # a bad param is fatal at start-up (the caller logs it)
        self.handles: Dict[str, TurtleHandles] = {}
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, name="turtlesim_update", daemon=True)
        rospy.Service("clear", Empty, self.on_clear)
        rospy.Service("reset", Empty, self.on_reset)
        rospy.Service("spawn", Spawn, self.on_spawn)
        rospy.Service("kill", Kill, self.on_kill)
        rospy.loginfo("Starting turtlesim with node name %s", rospy.get_name())
        with self.lock:
            self._spawn("", WORLD_SIZE / 2.0, WORLD_SIZE / 2.0, 0.0)

    # --- lifetime ------------------------------------------------------------------------------------------------
    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(2.0)

    def _loop(self) -> None:
        """One world update every UPDATE_PERIOD of wall time, on a fixed schedule (so 1 s holds 62.5 updates); an
        update that fails is logged (throttled) and the next one comes as usual."""
        next_update = time.monotonic()
        while not self._stop.is_set() and not rospy.is_shutdown():
            try:
                self.step(time.monotonic())
            except Exception as error:  # never ends the loop: /pose must go on
                rospy.logerr_throttle(WARNING_PERIOD, "turtlesim update failed: %s: %s" % (type(error).__name__, error))
            next_update += UPDATE_PERIOD
            delay = next_update - time.monotonic()
            if delay < -MAX_LAG:
                next_update = time.monotonic()
            elif delay > 0:
                self._stop.wait(delay)

    def step(self, now: float) -> None:
        with self.lock:
            hits = self.world.update(now)
            for fault in self.world.take_faults():
                rospy.logwarn_throttle(WARNING_PERIOD, fault)
            for name, turtle in self.world.turtles.items():
                handles = self.handles[name]
                handles.pose_pub.publish(Pose(turtle.x, turtle.y, turtle.theta, turtle.linear_velocity, turtle.ang))
                handles.colour_pub.publish(Color(*self.world.colour_under(turtle)))
            for hit in hits:
                handles = self.handles[hit.name]
                if now - handles.last_wall_warning >= WALL_WARNING_PERIOD:
                    handles.last_wall_warning = now
                    rospy.logwarn(hit.message())

    # --- world services ------------------------------------------------------------------------------------------
    def _spawn(self, name: str, x: float, y: float, theta: float) -> str:
        name = self.world.spawn(name, x, y, theta)
        try:
            self.handles[name] = TurtleHandles(self, name)
        except (ValueError, rospy.ROSException) as error:  # all or nothing: the turtle goes again
            self.world.kill(name)
            raise WorldError("Cannot spawn turtle [%s]: %s" % (name, error)) from None
        rospy.loginfo("Spawning turtle [%s] at x=[%f], y=[%f], theta=[%f]", name, x, y, theta)
        return name

    def on_spawn(self, req) -> SpawnResponse:
        with self.lock:
            try:
                return SpawnResponse(self._spawn(req.name, req.x, req.y, req.theta))
            except WorldError as error:
                rospy.logerr(str(error))
                raise rospy.ServiceException(str(error))

    def on_kill(self, req) -> KillResponse:
        with self.lock:
            try:
                self.world.kill(req.name)
            except WorldError as error:
                rospy.logerr(str(error))
                raise rospy.ServiceException(str(error))
            self.handles.pop(req.name).close()
        return KillResponse()

    def on_clear(self, _req) -> EmptyResponse:
        rospy.loginfo("Clearing turtlesim.")
        background = self._background_or_refuse()
        with self.lock:
            self.world.clear(background)
        return EmptyResponse()

    def on_reset(self, _req) -> EmptyResponse:
        rospy.loginfo("Resetting turtlesim.")
        background = self._background_or_refuse()
        with self.lock:
            for handles in self.handles.values():
                handles.close()
            self.handles.clear()
            self.world.reset(background)
            name = next(iter(self.world.turtles))
            self.handles[name] = TurtleHandles(self, name)
            turtle = self.world.turtles[name]
            rospy.loginfo("Spawning turtle [%s] at x=[%f], y=[%f], theta=[%f]", name, turtle.x, turtle.y, turtle.theta)
        return EmptyResponse()

    @staticmethod
    def _background_or_refuse() -> Rgb:
        try:
            return read_background()
        except rospy.ServiceException as error:
            rospy.logerr(str(error))
            raise

    # --- per-turtle topics and services --------------------------------------------------------------------------
    def on_cmd_vel(self, msg: Twist, name: str) -> None:
        with self.lock:
            turtle = self.world.turtles.get(name)
            if turtle is None:
                return
            try:
                turtle.command(msg.linear.x, msg.linear.y, msg.angular.z, time.monotonic())
            except WorldError as error:
                rospy.logwarn_throttle(WARNING_PERIOD, "%s: ignored" % error)

    def _on_turtle(self, name: str, action) -> None:
        """Run action() on the world under the lock; a turtle killed meanwhile fails the call with a message."""
        with self.lock:
            try:
                action()
            except WorldError as error:
                rospy.logerr(str(error))
                raise rospy.ServiceException(str(error))

    def on_set_pen(self, name: str, req) -> SetPenResponse:
        self._on_turtle(name, lambda: self.world.set_pen(name, (req.r, req.g, req.b), req.width, bool(req.off)))
        return SetPenResponse()

    def on_teleport_absolute(self, name: str, req) -> TeleportAbsoluteResponse:
        self._on_turtle(name, lambda: self.world.teleport_absolute(name, req.x, req.y, req.theta))
        return TeleportAbsoluteResponse()

    def on_teleport_relative(self, name: str, req) -> TeleportRelativeResponse:
        self._on_turtle(name, lambda: self.world.teleport_relative(name, req.linear, req.angular))
        return TeleportRelativeResponse()

    # --- for the window ------------------------------------------------------------------------------------------
    def snapshot(self, canvas_version: int) -> Tuple[int, bytes, List[Tuple[float, float, float]]]:
        """(canvas version, the canvas as PPM if it changed since `canvas_version` else b"", turtle poses)."""
        with self.lock:
            canvas = self.world.canvas
            image = canvas.ppm() if canvas.version != canvas_version else b""
            poses = [(t.x, t.y, t.theta) for t in self.world.turtles.values()]
            return canvas.version, image, poses
