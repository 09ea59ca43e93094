"""Node cmd_vel_mux: yocs_cmd_vel_mux's velocity multiplexer as a plain node (the real one is a nodelet).

Private topics as upstream's: ~<topic> of each configured input in, ~output (or the yaml's `publisher`) out,
~active latched (the active input's name, or "idle").
"""
from __future__ import annotations

import threading

import rospy
import yaml
from geometry_msgs.msg import Twist
from std_msgs.msg import String

from yocs_cmd_vel_mux.mux import CmdVelMux, ConfigError, parse_inputs

# How often (sim time) timeouts are checked; commands themselves also check them.
TICK_S = 0.02


def load_config() -> dict:
    data = rospy.get_param("~yaml_cfg_data", "")
    path = rospy.get_param("~yaml_cfg_file", "")
    try:
        if data:
            return yaml.safe_load(data) or {}
        with open(path) as config_file:
            return yaml.safe_load(config_file) or {}
    except (OSError, yaml.YAMLError) as error:
        raise ConfigError("~yaml_cfg_file [%s]: %s" % (path, error))


class MuxNode:
    def __init__(self) -> None:
        config = load_config()
        if not isinstance(config, dict):
            raise ConfigError("the configuration must be a mapping, got [%r]" % (config,))
        self._mux = CmdVelMux(parse_inputs(config.get("subscribers")))
        self._lock = threading.Lock()
        self._active_pub = rospy.Publisher("~active", String, queue_size=1, latch=True)
        self._active_pub.publish(String(data=self._mux.active))
        self._output = rospy.Publisher("~" + str(config.get("publisher", "output")), Twist, queue_size=10)
        self._subs = [
            rospy.Subscriber("~" + source.topic, Twist, self._on_command, callback_args=index, queue_size=10)
            for index, source in enumerate(self._mux.inputs)
        ]
        self._timer = rospy.Timer(rospy.Duration(TICK_S), self._on_tick)
        for source in self._mux.inputs:
            rospy.loginfo(
                "cmd_vel_mux: [%s] on [%s], priority %d, timeout %.2f s",
                source.name,
                rospy.resolve_name("~" + source.topic),
                source.priority,
                source.timeout,
            )

    def _on_command(self, msg: Twist, index: int) -> None:
        with self._lock:
            before = self._mux.active
            forward = self._mux.command(index, rospy.get_time())
            self._announce(before)
            if forward:
                self._output.publish(msg)

    def _on_tick(self, _event) -> None:
        with self._lock:
            before = self._mux.active
            if self._mux.expire(rospy.get_time()):
                self._announce(before)

    def _announce(self, before: str) -> None:
        if self._mux.active != before:
            self._active_pub.publish(String(data=self._mux.active))


def main() -> int:
    rospy.init_node("cmd_vel_mux")
    try:
        MuxNode()
    except ConfigError as error:
        rospy.logfatal("cmd_vel_mux: %s", error)
        return 1
    rospy.spin()  # returns at shutdown; it raises no ROSInterruptException (rospy/client.py, spin)
    return 0
