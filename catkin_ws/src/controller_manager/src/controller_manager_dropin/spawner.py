"""`rosrun controller_manager spawner [--stopped] [--wait-for topic] [--namespace ns] [--timeout T] [--no-timeout]
[--shutdown-timeout T] controller... `: loads the controllers (a YAML file's names after loading the file onto the
parameter server), starts them (unless --stopped), and on shutdown stops and unloads them, as ros_control's
Noetic spawner does, with its log messages."""
from __future__ import annotations

import argparse
import os
import time
from typing import List, Optional

import rosparam
import rospy
import yaml
from controller_manager_msgs.srv import SwitchController, SwitchControllerRequest, UnloadController
from std_msgs.msg import Bool

from controller_manager_dropin.services import proxy, service_name


def parse_args(args: Optional[List[str]] = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description="Controller spawner")
    parser.add_argument("--stopped", action="store_true", help="loads controllers, but does not start them")
    parser.add_argument(
        "--wait-for", metavar="topic", help='does not load or start controllers until it hears "True" on a topic (Bool)'
    )
    parser.add_argument("--namespace", metavar="ns", help="namespace of the controller_manager services")
    parser.add_argument(
        "--timeout",
        metavar="T",
        type=float,
        default=30,
        help="how long to wait for controller_manager services when starting up [s] (default: 30). <=0 waits "
        "indefinitely.",
    )
    parser.add_argument(
        "--no-timeout",
        action="store_true",
        help="wait for controller_manager services indefinitely (same as `--timeout 0`)",
    )
    parser.add_argument("--shutdown-timeout", help="DEPRECATED: this argument has no effect.")
    parser.add_argument("controllers", metavar="controller", nargs="+", help="controllers to load")
    return parser.parse_args(args=args)


class Spawner:
    def __init__(self, namespace: str) -> None:
        self.namespace = namespace
        self.loaded: List[str] = []

    def wait_for_services(self, timeout: Optional[float]) -> bool:
        """Upstream waits again while sim time has not started (a paused Gazebo before its first /clock)."""
        while True:
            try:
                self.load = self._proxy("load_controller", timeout)
                self.switch = self._proxy("switch_controller", timeout)
                self._proxy("unload_controller", timeout)
                return True
            except rospy.ROSException:
                if rospy.get_param("/use_sim_time", False) and rospy.get_rostime() == rospy.Time(0):
                    rospy.loginfo("Waiting for /clock to be available...")
                else:
                    rospy.logwarn("Controller Spawner couldn't find the expected controller_manager ROS interface.")
                    return False

    def _proxy(self, name: str, timeout: Optional[float]):
        rospy.loginfo("Controller Spawner: Waiting for service " + service_name(name, self.namespace))
        return proxy(name, self.namespace, timeout)

    def shutdown(self) -> None:
        rospy.loginfo("Shutting down spawner. Stopping and unloading controllers...")
        try:
            unload = rospy.ServiceProxy(service_name("unload_controller", self.namespace), UnloadController)
            switch = rospy.ServiceProxy(service_name("switch_controller", self.namespace), SwitchController)
            rospy.loginfo("Stopping all controllers...")
            switch([], self.loaded, SwitchControllerRequest.STRICT, False, 0.0)
            rospy.loginfo("Unloading all loaded controllers...")
            for name in reversed(self.loaded):
                rospy.loginfo("Trying to unload %s" % name)
                unload(name)
                rospy.loginfo("Succeeded in unloading %s" % name)
        except (rospy.ServiceException, rospy.exceptions.ROSException) as error:
            rospy.logwarn("Controller Spawner error while taking down controllers: %s" % error)

    def spawn(self, names: List[str], start: bool) -> None:
        for name in names:
            rospy.loginfo("Loading controller: " + name)
            if self.load(name).ok:
                self.loaded.append(name)
            else:
                time.sleep(1)  # as upstream: gives the manager's error message a chance to get out first
                rospy.logerr("Failed to load %s" % name)
        rospy.loginfo("Controller Spawner: Loaded controllers: %s" % ", ".join(self.loaded))
        if rospy.is_shutdown() or not start:
            return
        if self.switch(self.loaded, [], SwitchControllerRequest.STRICT, False, 0.0).ok:
            rospy.loginfo("Started controllers: %s" % ", ".join(self.loaded))
        else:
            rospy.logerr("Failed to start controllers: %s" % ", ".join(self.loaded))


def controller_names(arguments: List[str]) -> List[str]:
    """A YAML file among the arguments is loaded onto the parameter server; its top-level keys are controllers."""
    names: List[str] = []
    for argument in arguments:
        if os.path.exists(argument):
            with open(argument) as stream:
                rosparam.set_param("", stream.read())
            with open(argument) as stream:
                names += list(yaml.safe_load(stream) or {})
        else:
            names.append(argument)
    return names


def wait_for_true(topic: str, timeout: Optional[float]) -> bool:
    heard: List[Bool] = []
    rospy.Subscriber(topic, Bool, heard.append)
    started, warned = time.time(), False
    while not (heard and heard[-1].data):
        time.sleep(0.01)
        if rospy.is_shutdown():
            return False
        if not heard and not warned and timeout is not None and time.time() - started > timeout:
            warned = True
            rospy.logwarn('Controller Spawner hasn\'t heard anything from its "wait for" topic (%s)' % topic)
    return True


def main() -> None:
    args = parse_args(rospy.myargv()[1:])
    timeout = None if args.no_timeout or args.timeout <= 0 else args.timeout
    rospy.init_node("spawner", anonymous=True)
    if args.shutdown_timeout is not None:
        rospy.logwarn("DEPRECATION warning: --shutdown-timeout has no effect.")
    spawner = Spawner(args.namespace or "")
    if not spawner.wait_for_services(timeout):
        return
    if args.wait_for and not wait_for_true(args.wait_for, timeout):
        return
    rospy.on_shutdown(spawner.shutdown)
    spawner.spawn(controller_names(args.controllers), start=not args.stopped)
    rospy.spin()
