"""The camera plugins' topics (sensors.plugins.camera): ros.camera_topics's CameraPublisher of the sensor; for
libgazebo_ros_triggered_camera.so one frame (image and camera_info) for each std_msgs/Empty on ``triggerTopicName`` in
the camera's namespace (GazeboRosTriggeredCamera: triggers count, a frame takes one; when, see sensors.trigger)."""
from __future__ import annotations

from typing import Callable, List, Optional, Sequence, Tuple

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
from turtle_sim_ode.sensors.trigger import TriggeredFrames


class TriggeredCameraPublisher(CameraPublisher):
    """A frame per trigger (image and camera_info), rendered at the first step after it and sent
    sensors.trigger.TRIGGERED_FRAME_DELAY_S of sim time later, as Gazebo's render loop beside its physics sends it."""

    def __init__(
        self,
        sensor: CameraSensor,
        scene: Scene,
        namespace: str,
        sun: Optional[Callable[[], Optional[Tuple[float, float, float]]]] = None,
        lights: Optional[Callable[[], Sequence[Light]]] = None,
        pace_from_now: Callable[[], None] = lambda: None,
    ) -> None:
        """``pace_from_now``: ModelContext's, called after each rendering."""
        super().__init__(sensor, scene, namespace, sun, lights)
        self._period = 0.0  # looks for a trigger at every step; renders only when triggered
        self._pace_from_now = pace_from_now
        self.frames: TriggeredFrames[Tuple[rospy.Time, Optional[Frame]]] = TriggeredFrames()
        topic = self.topic(sensor.config.trigger_topic)
        self._trigger_sub = subscriber(topic, Empty, lambda _message: self.frames.trigger(), 1)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        for taken, frame in self.frames.due(now):
            self.send(taken, frame)
        if self.frames.take():
            self.frames.hold(now, (stamp, self.render()))
            # Gazebo renders beside its physics: sim time stood still for this rendering and is not raced to
            # catch it up, so what answers a frame or the /clock after it does so within its usual sim time.
            self._pace_from_now()

    def restart(self, now: float) -> None:
        super().restart(now)
        self.frames.clear()

    def close(self) -> None:
        release(self._trigger_sub)
        super().close()


def interfaces(context: ModelContext, config: CameraConfig) -> List[Periodic]:
    sim = context.sim
    sensor = CameraSensor(sim.physics, context.model, config, sun_direction=sim.light_direction, sky=sim.sky_colour)
    # the world's lights as the light services leave them, read at each frame
    sun, lights = (lambda: sim.light_direction), (lambda: sim.camera_lights)
    if config.triggered:
        return [TriggeredCameraPublisher(sensor, sim.scene, context.namespace, sun, lights, context.pace_from_now)]
    return [CameraPublisher(sensor, sim.scene, context.namespace, sun, lights)]


def multicamera_interfaces(context: ModelContext, config: MultiCameraConfig) -> List[Periodic]:
    """gazebo_ros_multicamera: a camera's topics for each of its cameras, on one schedule (identical stamps)."""
    return [interface for single in config.cameras for interface in interfaces(context, single)]
