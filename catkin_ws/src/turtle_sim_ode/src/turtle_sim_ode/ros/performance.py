"""``/gazebo/performance_metrics`` (gazebo_msgs/PerformanceMetrics), as Gazebo 11 with gazebo_ros offers it
(gazebo_ros_api_plugin.cpp, onPerformanceMetrics: Gazebo's metrics republished while the topic has subscribers,
stamped with ROS time now; a sensor without a frame rate gets fps -1). Gazebo publishes them about once a wall
second: the real-time factor (sim time over wall time since the last message) and one entry per sensor of every
model's links, named world::model::link::sensor, with its update rate in sim time and in wall time and, for
cameras, their frame rate. Here a sensor's wall-time rate is its sim-time rate times the real-time factor (0 Hz:
every step), and a camera's fps that same rate (its frames fall due at it; they are rendered only while
subscribed)."""
from __future__ import annotations

import time
from typing import List, Tuple

import rospy
from gazebo_msgs.msg import PerformanceMetrics, SensorPerformanceMetric

from turtle_sim_ode.models.text import child_text, read_number
from turtle_sim_ode.ros.wire import heard
from turtle_sim_ode.world.simulation import Simulation

PERIOD = 1.0  # s of wall time between messages
CAMERA_TYPES = ("camera", "depth", "multicamera", "wideanglecamera")
NO_FPS = -1.0  # gazebo_ros: a sensor whose metrics have no fps


def sensor_rates(sim: Simulation, world_name: str) -> List[Tuple[str, float, bool]]:
    """(scoped name, update rate in Hz of sim time with 0 as every step, is a camera) of every model's sensors."""
    found = []
    for model_name, model in sim.models.items():
        for sensor in model.robot.sensors:
            element = sensor.element
            name = "::".join((world_name, model_name, sensor.link or "", element.get("name", "")))
            text = child_text(element, "update_rate")
            try:
                rate = read_number(text, "<update_rate>", 0.0, 0.0)
            except ValueError:  # refused at spawn already; never here
                rate = 0.0
            found.append((name, rate, element.get("type", "") in CAMERA_TYPES))
    return found


class PerformanceMetricsPublisher:
    """Publishes at most once per PERIOD of wall time, and only while subscribed (``publish_due`` from the sim
    loop, under the world lock)."""

    def __init__(self, sim: Simulation) -> None:
        self._sim = sim
        self._pub = rospy.Publisher("~performance_metrics", PerformanceMetrics, queue_size=10)
        self._last: Tuple[float, float] = (-1.0, 0.0)  # (wall, sim) at the last message; wall < 0: none yet

    def publish_due(self, sim_time: float) -> None:
        last_wall, last_sim = self._last
        if last_wall < 0 and not heard(self._pub):  # the common case, at every step: nobody listens
            return
        wall = time.monotonic()
        if 0 <= last_wall and wall - last_wall < PERIOD:
            return
        if not heard(self._pub):
            self._last = (-1.0, 0.0)
            return
        self._last = (wall, sim_time)
        if last_wall < 0 or sim_time <= last_sim:  # the first second, a pause or a reset: nothing to compare
            return
        factor = (sim_time - last_sim) / (wall - last_wall)
        message = PerformanceMetrics(real_time_factor=factor)
        message.header.stamp = rospy.Time.now()
        every_step = 1.0 / self._sim.physics.time_step
        for name, rate, camera in sensor_rates(self._sim, self._sim.world_name):
            rate = rate or every_step
            message.sensors.append(
                SensorPerformanceMetric(
                    name=name,
                    sim_update_rate=rate,
                    real_update_rate=rate * factor,
                    fps=rate * factor if camera else NO_FPS,
                )
            )
        self._pub.publish(message)
