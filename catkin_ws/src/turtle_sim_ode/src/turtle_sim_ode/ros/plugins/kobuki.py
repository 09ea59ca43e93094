"""kobuki_gazebo_plugins' topics (world.plugins.kobuki): the drive's, turtlebot_gazebo's ground truth, the gyro on
``<model>/sensors/imu_data`` and the bumper and cliff events."""
from __future__ import annotations

from typing import List

import rospy
from turtle_sim_ode_msgs.msg import BumperEvent, CliffEvent

from turtle_sim_ode.models.builder import BuiltModel
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, publisher, topic_prefix
from turtle_sim_ode.ros.plugin_topics import period
from turtle_sim_ode.ros.plugins.drive import DriveInterface
from turtle_sim_ode.ros.plugins.imu import ImuPublisher
from turtle_sim_ode.ros.plugins.p3d import GroundTruthPublisher
from turtle_sim_ode.ros.settings import SimulatorSettings
from turtle_sim_ode.ros.wire import release
from turtle_sim_ode.sensors.imu import ImuSensor
from turtle_sim_ode.sensors.kobuki import BumperSensor, CliffSensor
from turtle_sim_ode.world.plugins import DiffDriveRobot
from turtle_sim_ode.world.plugins.kobuki import KobukiConfig
from turtle_sim_ode.world.simulation import Simulation


class BumperEventPublisher(Periodic):
    """The Kobuki plugin's bumper events: one turtle_sim_ode_msgs/BumperEvent (= kobuki_msgs) per change."""

    def __init__(self, sensor: BumperSensor, topic: str, rate: float) -> None:
        super().__init__(period(rate))
        self._sensor = sensor
        self._pub = publisher(topic, BumperEvent, 10)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        for bumper, state in self._sensor.changes():  # every time, even unheard: events are changes
            self._pub.publish(BumperEvent(bumper=bumper, state=state))

    def close(self) -> None:
        self._sensor.close()
        release(self._pub)


class CliffEventPublisher(Periodic):
    """The Kobuki plugin's cliff events: one turtle_sim_ode_msgs/CliffEvent per change, with the distance to
    the floor in cm (``bottom``; the ray's range when it sees nothing)."""

    def __init__(self, sensor: CliffSensor, topic: str, rate: float) -> None:
        super().__init__(period(rate))
        self._sensor = sensor
        self._pub = publisher(topic, CliffEvent, 10)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        for sensor, state, distance in self._sensor.changes():
            bottom = int(round(min(distance, self._sensor.max_range) * 100.0))
            self._pub.publish(CliffEvent(sensor=sensor, state=state, bottom=bottom))

    def close(self) -> None:
        release(self._pub)


def kobuki_events(
    sim: Simulation, model: BuiltModel, robot: DiffDriveRobot, prefix: str, settings: SimulatorSettings
) -> List[Periodic]:
    """The Kobuki plugin's bumper and cliff events; its bumper and cliff sensors sit on base_link (kobuki_description),
    else on the root link."""
    link = "base_link" if model.geoms.get("base_link") else model.root_link
    if not model.geoms.get(link):
        rospy.logwarn("model %s: no collision geoms on [%s]: no bumper or cliff events", model.name, link)
        return []
    bumper = BumperSensor(sim.physics, model, link)
    events: List[Periodic] = []
    try:
        events.append(BumperEventPublisher(bumper, prefix + "bumper", settings.publish_rate))
        cliff = CliffSensor(sim.physics, model, link, robot.config.cliff_threshold)
        events.append(CliffEventPublisher(cliff, prefix + "cliff", settings.publish_rate))
    except BaseException:
        bumper.close()  # its contact watch: the publisher that would close it was refused
        raise
    return events


def interfaces(context: ModelContext, config: KobukiConfig) -> List[Periodic]:
    """The model's drive (if this is its first drive plugin) and what the Kobuki base publishes beside it."""
    name, sim, settings, namespace = context.name, context.sim, context.settings, context.namespace
    robot = sim.robots.get(name)
    if robot is None or robot.config is not config:
        return []
    model = context.model
    found: List[Periodic] = [DriveInterface(name, robot, settings, context.tf_broadcaster, sim, namespace)]
    # turtlebot_gazebo's ground-truth odometry of the base, under the node's parameters.
    base = settings.base_frame if settings.base_frame in model.links else model.root_link
    found.append(
        GroundTruthPublisher(
            model,
            base,
            topic_prefix(namespace) + settings.ground_truth_topic,
            settings.ground_truth_frame,
            settings.publish_rate,
            True,
        )
    )
    # The Kobuki plugin's gyro, on <model>/sensors/imu_data as kobuki_gazebo_plugins publishes it.
    imu_link = "imu_link" if "imu_link" in model.links else base
    imu = ImuSensor(model, imu_link, tuple(sim.physics.params.gravity))
    found.append(
        ImuPublisher(imu, topic_prefix(namespace) + name + "/sensors/imu_data", imu_link, settings.publish_rate)
    )
    found += kobuki_events(sim, model, robot, topic_prefix(namespace) + name + "/events/", settings)
    return found
