"""gazebo_ros_vacuum_gripper's ROS side (world.plugins.vacuum_gripper), as GazeboRosVacuumGripper::Load makes it in
the robot namespace (its <robotNamespace>, else the spawn's robot_namespace): std_srvs/Empty services ``on`` and ``off`` (a second ``on`` or ``off`` warns and still answers),
and std_msgs/Bool on ``topicName``, published after every step: true while the gripper held a link in that step
(UpdateChild publishes at every world update, false while off). The gripper's work is a Simulation step hook, run
before each physics step."""
from __future__ import annotations

from typing import List

import rospy
from std_msgs.msg import Bool
from std_srvs.srv import Empty, EmptyResponse

from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.ros.names import legal_name, shown
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, packed_publisher, plugin_topic, topic_prefix
from turtle_sim_ode.ros.wire import release
from turtle_sim_ode.world.entities import SCOPE
from turtle_sim_ode.world.plugins.vacuum_gripper import VacuumGripper, VacuumGripperConfig

_TRUE, _FALSE = b"\x01", b"\x00"  # std_msgs/Bool on the wire


def _pack_bool(_seq: int, value: bool) -> bytes:
    return _TRUE if value else _FALSE


class VacuumGripperInterface(Periodic):
    def __init__(self, context: ModelContext, gripper: VacuumGripper, config: VacuumGripperConfig) -> None:
        super().__init__(0.0)  # every step, as upstream publishes at every world update
        self._gripper = gripper
        self._name = context.name
        namespace = context.namespace
        self.topic = plugin_topic(namespace, config.topic)
        self.services = [topic_prefix(namespace) + "on", topic_prefix(namespace) + "off"]
        for service in self.services:
            if not legal_name(service):
                raise ModelError(
                    f"model '{context.name}': vacuum gripper service {shown(service)!r} is not a legal ROS name "
                    f"(robotNamespace)"
                )
        self._pub = packed_publisher(self.topic, Bool)
        self._servers: List[rospy.Service] = []
        try:
            for service, handler in zip(self.services, (self._on, self._off)):
                self._servers.append(rospy.Service(service, Empty, handler))
        except BaseException as error:
            for server in self._servers:
                server.shutdown()  # the publisher is released by model_interfaces
            if isinstance(error, rospy.ServiceException):  # another vacuum gripper offers it (in the same namespace)
                raise ModelError(f"model '{context.name}': vacuum gripper: {error} (set another robotNamespace)")
            raise
        self._sim = context.sim
        self._key = f"{context.name}{SCOPE}vacuum_gripper{SCOPE}{id(gripper)}"
        context.sim.step_hooks[self._key] = gripper
        rospy.loginfo("model %s: vacuum gripper on link [%s], status on [%s]", self._name, gripper.link, self.topic)

    def _on(self, _request: object) -> EmptyResponse:
        if self._gripper.switch_on():
            rospy.loginfo("gazebo_ros_vacuum_gripper (%s): status: off -> on", self._name)
        else:
            rospy.logwarn("gazebo_ros_vacuum_gripper (%s): already status is 'on'", self._name)
        return EmptyResponse()

    def _off(self, _request: object) -> EmptyResponse:
        if self._gripper.switch_off():
            rospy.loginfo("gazebo_ros_vacuum_gripper (%s): status: on -> off", self._name)
        else:
            rospy.logwarn("gazebo_ros_vacuum_gripper (%s): already status is 'off'", self._name)
        return EmptyResponse()

    def publish(self, stamp: rospy.Time, now: float) -> None:
        self._pub.publish(_pack_bool, self._gripper.grasping)

    def close(self) -> None:
        if self._sim.step_hooks.get(self._key) is self._gripper:
            del self._sim.step_hooks[self._key]
        for server in self._servers:
            server.shutdown()
        release(self._pub)


def interfaces(context: ModelContext, config: VacuumGripperConfig) -> List[Periodic]:
    """The plugin's ROS side; a gripper link the model does not keep is logged with the links found (as upstream's
    fatal messages) and the model goes on without the plugin."""
    try:
        gripper = VacuumGripper(context.model, config.body, context.sim.models)
    except ModelError as error:
        rospy.logerr("gazebo_ros_vacuum_gripper plugin error: %s", error)
        return []
    return [VacuumGripperInterface(context, gripper, config)]
