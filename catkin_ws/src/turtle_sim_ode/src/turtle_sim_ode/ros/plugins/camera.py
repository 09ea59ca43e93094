"""The camera plugins' topics (sensors.plugins.camera): ros.camera_topics's CameraPublisher of the sensor."""
from __future__ import annotations

from typing import List

from turtle_sim_ode.ros.camera_topics import CameraPublisher
from turtle_sim_ode.ros.periodic import ModelContext, Periodic
from turtle_sim_ode.sensors.camera import CameraSensor
from turtle_sim_ode.sensors.plugins.camera import CameraConfig


def interfaces(context: ModelContext, config: CameraConfig) -> List[Periodic]:
    sim = context.sim
    sensor = CameraSensor(sim.physics, context.model, config, sun_direction=sim.light_direction, sky=sim.sky_colour)
    return [CameraPublisher(sensor, sim.scene, context.namespace)]
