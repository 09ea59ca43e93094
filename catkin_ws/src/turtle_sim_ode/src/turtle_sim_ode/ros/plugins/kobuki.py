"""kobuki_gazebo_plugins' topics (world.plugins.kobuki): the drive's, turtlebot_gazebo's ground truth, the gyro on
``<model>/sensors/imu_data``, the bumper, cliff and wheel-drop events, the core sensor state and motor power."""
from __future__ import annotations

from typing import Any, Callable, List

import rospy
from kobuki_msgs.msg import BumperEvent, CliffEvent, MotorPower, SensorState, WheelDropEvent

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, publisher, subscriber, topic_prefix
from turtle_sim_ode.ros.plugin_topics import KOBUKI_JOINT_STATES_FRAME, period
from turtle_sim_ode.ros.plugins.drive import DriveInterface
from turtle_sim_ode.ros.plugins.imu import ImuPublisher
from turtle_sim_ode.ros.plugins.p3d import GroundTruthPublisher
from turtle_sim_ode.ros.settings import SimulatorSettings
from turtle_sim_ode.ros.wire import heard, release
from turtle_sim_ode.sensors.imu import ImuSensor
from turtle_sim_ode.sensors.kobuki import (
    KOBUKI_CLIFF_OFFSETS,
    STATE_BITS_LCR,
    STATE_BITS_WHEELS,
    BumperSensor,
    CliffSensor,
    WheelDropSensor,
    offsets_in,
    sensor_links,
    state_bits,
)
from turtle_sim_ode.world.plugins import DiffDriveRobot
from turtle_sim_ode.world.plugins.kobuki import KobukiConfig
from turtle_sim_ode.world.simulation import Simulation


class EventPublisher(Periodic):
    """One kind of the Kobuki plugin's events, one message per change of its sensor's state. The sensor is read only
    while someone listens to these events or to the core sensor state (``core_heard``), which reports the state the
    events last reported: read unheard, it cost a third of the node's stepping at 10 ms steps (issue #33). A change
    is one from the state last read: a listener that comes after a change made while nobody listened hears of it at
    the first reading (kobuki_gazebo_plugins, reading all along, would not tell it), and one that subscribes just
    before a change hears of it as there."""

    def __init__(self, sensor: Any, topic: str, msg_type: type, rate: float, core_heard: Callable[[], bool]) -> None:
        super().__init__(period(rate))
        self._sensor = sensor
        self._pub = publisher(topic, msg_type, 10)
        self._core_heard = core_heard

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if heard(self._pub) or self._core_heard():
            for change in self._sensor.changes():
                self._pub.publish(self.message(*change))

    def message(self, *change: Any) -> Any:
        raise NotImplementedError

    def close(self) -> None:
        release(self._pub)


class BumperEventPublisher(EventPublisher):
    """The Kobuki plugin's bumper events: kobuki_msgs/BumperEvent."""

    def __init__(self, sensor: BumperSensor, topic: str, rate: float, core_heard: Callable[[], bool]) -> None:
        super().__init__(sensor, topic, BumperEvent, rate, core_heard)

    def message(self, bumper: int, state: int) -> BumperEvent:  # type: ignore[override]
        return BumperEvent(bumper=bumper, state=state)

    def close(self) -> None:
        self._sensor.close()
        super().close()


class CliffEventPublisher(EventPublisher):
    """The Kobuki plugin's cliff events: kobuki_msgs/CliffEvent, with the distance to the floor in cm (``bottom``;
    the ray's range when it sees nothing)."""

    def __init__(self, sensor: CliffSensor, topic: str, rate: float, core_heard: Callable[[], bool]) -> None:
        super().__init__(sensor, topic, CliffEvent, rate, core_heard)

    def message(self, sensor: int, state: int, distance: float) -> CliffEvent:  # type: ignore[override]
        bottom = int(round(min(distance, self._sensor.max_range) * 100.0))
        return CliffEvent(sensor=sensor, state=state, bottom=bottom)


class WheelDropEventPublisher(EventPublisher):
    """The Kobuki plugin's wheel-drop events: kobuki_msgs/WheelDropEvent."""

    def __init__(self, sensor: WheelDropSensor, topic: str, rate: float, core_heard: Callable[[], bool]) -> None:
        super().__init__(sensor, topic, WheelDropEvent, rate, core_heard)

    def message(self, wheel: int, state: int) -> WheelDropEvent:  # type: ignore[override]
        return WheelDropEvent(wheel=wheel, state=state)

    def close(self) -> None:
        self._sensor.close()
        super().close()


class CorePublisher(Periodic):
    """``<model>/sensors/core``: kobuki_msgs/SensorState with the bumper, cliff and wheel-drop bits as the event
    publishers (listed before it, so updated first in each cycle) last reported them; the other fields stay 0, as
    kobuki_gazebo_plugins leaves them."""

    def __init__(
        self, bumper: BumperSensor, cliff: CliffSensor, drops: WheelDropSensor, topic: str, rate: float
    ) -> None:
        super().__init__(period(rate))
        self._sensors = (bumper, cliff, drops)
        self._pub = publisher(topic, SensorState, 10)

    def heard(self) -> bool:
        return heard(self._pub)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not self.heard():
            return
        bumper, cliff, drops = self._sensors
        state = SensorState(
            bumper=state_bits(bumper.state, STATE_BITS_LCR),
            cliff=state_bits(cliff.state, STATE_BITS_LCR),
            wheel_drop=state_bits(drops.state, STATE_BITS_WHEELS),
        )
        state.header.stamp = stamp
        self._pub.publish(state)

    def close(self) -> None:
        release(self._pub)


class MotorPowerListener(Periodic):
    """``<model>/commands/motor_power``: kobuki_msgs/MotorPower OFF holds the wheels and drops velocity commands
    until ON (kobuki_gazebo_plugins' motorPowerCB); publishes nothing."""

    def __init__(self, name: str, robot: DiffDriveRobot, topic: str) -> None:
        super().__init__(float("inf"))
        self._name = name
        self._robot = robot
        self._sub = subscriber(topic, MotorPower, self._on_power, 10)

    def _on_power(self, msg: MotorPower) -> None:
        if msg.state not in (MotorPower.ON, MotorPower.OFF):
            rospy.logwarn_throttle(
                5.0, "%s: motor power state [%d] is neither ON nor OFF: ignored", self._name, msg.state
            )
            return
        enabled = msg.state == MotorPower.ON
        if enabled != self._robot.drive.motors_enabled:
            self._robot.drive.motors_enabled = enabled  # read by the simulation thread before each step
            rospy.loginfo("%s: motors %s", self._name, "on" if enabled else "off")

    def publish(self, stamp: rospy.Time, now: float) -> None:
        pass

    def close(self) -> None:
        release(self._sub)


def kobuki_sensors(
    sim: Simulation, model: BuiltModel, robot: DiffDriveRobot, prefix: str, settings: SimulatorSettings
) -> List[Periodic]:
    """The Kobuki plugin's bumper, cliff and wheel-drop events and its core sensor state, from the model's sensors
    the plugin names (kobuki_description's: the bumpers' contact sensor on base_link, three cliff rays, a contact
    sensor on each wheel); without them, on base_link (else the root link) with kobuki_description's cliff
    positions, and on the wheel joints' links."""
    config = robot.config
    contacts, rays = sensor_links(model.robot, "contact"), sensor_links(model.robot, "ray")
    link = contacts.get(config.bumper_sensor) or ("base_link" if model.geoms.get("base_link") else model.root_link)
    if not model.geoms.get(link):
        rospy.logwarn("model %s: no collision geoms on [%s]: no bumper, cliff or wheel-drop events", model.name, link)
        return []
    cliff_links = [rays.get(sensor) for sensor in config.cliff_sensors]
    cliff_offsets = offsets_in(model, link, cliff_links) if all(cliff_links) else KOBUKI_CLIFF_OFFSETS
    wheels = [contacts.get(sensor) for sensor in config.wheel_drop_sensors]
    if not all(wheels):
        wheels = [model.robot.joints[wheel.name].child for wheel in (robot.left, robot.right)]
    if not all(model.geoms.get(wheel) for wheel in wheels):
        rospy.logwarn("model %s: wheel links %s without collision geoms: no wheel-drop events", model.name, wheels)
        wheels = []
    sensors: list = [BumperSensor(sim.physics, model, link)]
    found: List[Periodic] = []
    try:
        sensors.append(CliffSensor(sim.physics, model, link, config.cliff_threshold, cliff_offsets))
        sensors.append(WheelDropSensor(sim.physics, model, wheels))
        bumper, cliff, drops = sensors
        rate = settings.publish_rate
        # Made first (the events ask whether it is heard), listed last: the events read their sensors first in each
        # cycle.
        core = CorePublisher(bumper, cliff, drops, prefix + "sensors/core", rate)
        found.append(core)
        found.insert(-1, BumperEventPublisher(bumper, prefix + "events/bumper", rate, core.heard))
        found.insert(-1, CliffEventPublisher(cliff, prefix + "events/cliff", rate, core.heard))
        found.insert(-1, WheelDropEventPublisher(drops, prefix + "events/wheel_drop", rate, core.heard))
    except BaseException:
        for periodic in found:
            periodic.close()
        for sensor in sensors:  # their contact watches (closing twice is harmless)
            if hasattr(sensor, "close"):
                sensor.close()
        raise
    return found


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
    # The gyro: the link of the imu sensor the plugin names, whose readings kobuki_gazebo_plugins stamps with
    # base_link's frame (updateIMU copies the joint states' header); else the simulator's own TurtleBot's imu_link.
    named = sensor_links(model.robot, "imu").get(config.imu_sensor)
    imu_link = named or ("imu_link" if "imu_link" in model.links else base)
    imu_frame = KOBUKI_JOINT_STATES_FRAME if named else imu_link
    imu = ImuSensor(model, imu_link, tuple(sim.physics.params.gravity))
    found.append(
        ImuPublisher(imu, topic_prefix(namespace) + name + "/sensors/imu_data", imu_frame, settings.publish_rate)
    )
    found += kobuki_sensors(sim, model, robot, topic_prefix(namespace) + name + "/", settings)
    found.append(MotorPowerListener(name, robot, topic_prefix(namespace) + name + "/commands/motor_power"))
    return found
