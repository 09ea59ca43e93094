"""The dynamic_reconfigure servers of hector_gazebo_plugins' sensors: one server a namespace, its callback a
ROS-free function of the config and the level that returns the values to publish; a ValueError from it (a value
refused) is a throttled warning and the current values are published instead. ``sensor_model_server`` serves an
error model (hector_gazebo_plugins/SensorModelConfig, SensorModel_::dynamicReconfigureCallback)."""
from __future__ import annotations

from typing import Any, Callable, Dict, Iterable

from dynamic_reconfigure.server import Server
from hector_gazebo_plugins.cfg import SensorModelConfig

from turtle_sim_ode.ros.throttle import logwarn_every
from turtle_sim_ode.world.plugins.hector_sensor_model import SensorError, current_values, reconfigure

Values = Dict[str, Any]


def reconfigure_server(
    config_type: Any,
    where: str,
    apply: Callable[[Values, int], Values],
    current: Callable[[], Values],
    sensor: str,
) -> Server:
    """A server at ``where`` (a resolved name) calling ``apply(config, level)``; ``current()`` when it refuses.
    ``sensor`` names the plugin in the warning."""

    def handle(config: Values, level: int) -> Values:
        try:
            config.update(apply(config, level))
        except ValueError as refused:
            logwarn_every(5.0, f"{sensor} reconfigure {where}", f"{sensor} {where}: reconfiguration ignored: {refused}")
            config.update(current())
        return config

    return Server(config_type, handle, namespace=where)


def sensor_model_server(error: SensorError, where: str, sensor: str, scalar: bool = False) -> Server:
    """A SensorModelConfig server over ``error``'s model (``scalar``: reported by its first axis, as yaw's)."""
    return reconfigure_server(
        SensorModelConfig,
        where,
        lambda config, level: reconfigure(error, config, level, scalar),
        lambda: current_values(error.model, scalar),
        sensor,
    )


def close_servers(servers: Iterable[Server]) -> None:
    """dynamic_reconfigure's Python server has no shutdown of its own: its service and topics one by one."""
    for server in servers:
        server.set_service.shutdown()
        server.descr_topic.unregister()
        server.update_topic.unregister()
