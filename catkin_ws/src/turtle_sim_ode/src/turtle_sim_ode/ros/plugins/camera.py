"""The camera plugins' topics (sensors.plugins.camera): ros.camera_topics's CameraPublisher of the sensor; for
libgazebo_ros_triggered_camera.so one frame (image and camera_info) for each std_msgs/Empty on ``triggerTopicName`` in
the camera's namespace (GazeboRosTriggeredCamera: triggers count, a frame takes one), see TriggeredCameraPublisher."""
from __future__ import annotations

import threading
import time
from collections import deque
from typing import Callable, Deque, List, Optional, Sequence, Tuple

import rospy
from std_msgs.msg import Empty

from turtle_sim_ode.models.lights import Light
from turtle_sim_ode.ros.camera_topics import CameraPublisher
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, subscriber
from turtle_sim_ode.ros.wire import release
from turtle_sim_ode.sensors.camera import CameraSensor, Frame
from turtle_sim_ode.sensors.plugins.camera import CameraConfig
from turtle_sim_ode.sensors.plugins.multicamera import MultiCameraConfig
from turtle_sim_ode.sensors.scene import Scene


class TriggeredCameraPublisher(CameraPublisher):
    """A frame per trigger, rendered at the first step after it (the picture and stamp of that step, sim time
    standing still meanwhile) and published once sim time has moved on by as long as the rendering took (its wall
    time x the real-time factor; 1 when unpaced): Gazebo renders beside its physics, so a frame reaches subscribers
    that much sim time after its stamp."""

    def __init__(
        self,
        sensor: CameraSensor,
        scene: Scene,
        namespace: str,
        sun: Optional[Callable[[], Optional[Tuple[float, float, float]]]] = None,
        real_time_factor: Callable[[], float] = lambda: 1.0,
        lights: Optional[Callable[[], Sequence[Light]]] = None,
    ) -> None:
        super().__init__(sensor, scene, namespace, sun, lights)
        self._period = 0.0  # looks for a trigger at every step; renders only when triggered
        self._real_time_factor = real_time_factor
        self._lock = threading.Lock()
        self._triggers = 0
        self._held: Deque[Tuple[float, rospy.Time, Optional[Frame]]] = deque()  # (due sim time, stamp, frame)
        self._trigger_sub = subscriber(self.topic(sensor.config.trigger_topic), Empty, self._on_trigger, 1)

    def _on_trigger(self, _message: Empty) -> None:
        with self._lock:
            self._triggers += 1

    def publish(self, stamp: rospy.Time, now: float) -> None:
        while self._held and self._held[0][0] <= now + 1e-9:
            _, taken, frame = self._held.popleft()
            self.send(taken, frame)
        with self._lock:
            if not self._triggers:
                return
            self._triggers -= 1
        started = time.monotonic()
        frame = self.render()
        rtf = self._real_time_factor()
        self._held.append((now + (time.monotonic() - started) * (rtf if rtf > 0 else 1.0), stamp, frame))

    def restart(self, now: float) -> None:
        super().restart(now)
        self._held.clear()  # reset_simulation: frames of the old time are dropped

    def close(self) -> None:
        release(self._trigger_sub)
        super().close()


def interfaces(context: ModelContext, config: CameraConfig) -> List[Periodic]:
    sim = context.sim
    sensor = CameraSensor(sim.physics, context.model, config, sun_direction=sim.light_direction, sky=sim.sky_colour)
    # the world's lights as the light services leave them, read at each frame
    if config.triggered:
        rtf = lambda: sim.real_time_factor  # noqa: E731
        return [
            TriggeredCameraPublisher(
                sensor, sim.scene, context.namespace, lambda: sim.light_direction, rtf, lambda: sim.camera_lights
            )
        ]
    return [
        CameraPublisher(sensor, sim.scene, context.namespace, lambda: sim.light_direction, lambda: sim.camera_lights)
    ]


def multicamera_interfaces(context: ModelContext, config: MultiCameraConfig) -> List[Periodic]:
    """gazebo_ros_multicamera: a camera's topics for each of its cameras, on one schedule (identical stamps)."""
    return [interface for single in config.cameras for interface in interfaces(context, single)]
