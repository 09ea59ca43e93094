"""The camera plugins' topics (sensors.plugins.camera): ros.camera_topics's CameraPublisher of the sensor; for
libgazebo_ros_triggered_camera.so one frame (image and camera_info) at the step after each std_msgs/Empty on
``triggerTopicName`` in the camera's namespace (GazeboRosTriggeredCamera: triggers count, a frame takes one)."""
from __future__ import annotations

import threading
from typing import Callable, List, Optional, Tuple

import rospy
from std_msgs.msg import Empty

from turtle_sim_ode.ros.camera_topics import CameraPublisher
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, subscriber
from turtle_sim_ode.ros.wire import release
from turtle_sim_ode.sensors.camera import CameraSensor
from turtle_sim_ode.sensors.plugins.camera import CameraConfig
from turtle_sim_ode.sensors.plugins.multicamera import MultiCameraConfig
from turtle_sim_ode.sensors.scene import Scene


class TriggeredCameraPublisher(CameraPublisher):
    def __init__(
        self,
        sensor: CameraSensor,
        scene: Scene,
        namespace: str,
        sun: Optional[Callable[[], Optional[Tuple[float, float, float]]]] = None,
    ) -> None:
        super().__init__(sensor, scene, namespace, sun)
        self._period = 0.0  # looks for a trigger at every step; renders only when triggered
        self._lock = threading.Lock()
        self._triggers = 0
        self._trigger_sub = subscriber(self.topic(sensor.config.trigger_topic), Empty, self._on_trigger, 1)

    def _on_trigger(self, _message: Empty) -> None:
        with self._lock:
            self._triggers += 1

    def publish(self, stamp: rospy.Time, now: float) -> None:
        with self._lock:
            if not self._triggers:
                return
            self._triggers -= 1
        super().publish(stamp, now)

    def close(self) -> None:
        release(self._trigger_sub)
        super().close()


def interfaces(context: ModelContext, config: CameraConfig) -> List[Periodic]:
    sim = context.sim
    sensor = CameraSensor(sim.physics, context.model, config, sun_direction=sim.light_direction, sky=sim.sky_colour)
    kind = TriggeredCameraPublisher if config.triggered else CameraPublisher
    # the world's lights as the light services leave them, read at each frame
    return [kind(sensor, sim.scene, context.namespace, lambda: sim.light_direction)]


def multicamera_interfaces(context: ModelContext, config: MultiCameraConfig) -> List[Periodic]:
    """gazebo_ros_multicamera: a camera's topics for each of its cameras, on one schedule (identical stamps)."""
    return [interface for single in config.cameras for interface in interfaces(context, single)]
