#!/usr/bin/env python3
"""rostest node: twist_mux with test/graph_config.yaml (low: priority 10, high: 20, both timing out after 0.3 s;
lock stop: priority 15). Inputs are published at 20 Hz by a timer; expectations follow upstream's rules
(ros-teleop/twist_mux 3.1.3: twist_mux.cpp TwistMux::hasPriority, topic_handle.h VelocityTopicHandle::isMasked)
and diagnostics (twist_mux_diagnostics.cpp TwistMuxDiagnostics::diagnostics)."""
from __future__ import annotations

import threading
import unittest
from typing import Callable, Dict, List

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from geometry_msgs.msg import Twist
from std_msgs.msg import Bool

LOW, HIGH = 1.0, 2.0  # linear.x of each input's commands
# diagnostic_updater names a status "<node name without the leading slash>: <task>"
STATUS_NAME = "robot/twist_mux: Twist mux status"


class Recorder:
    """The messages of one topic, and a way to wait for one that satisfies a condition."""

    def __init__(self, topic: str, msg_type: type) -> None:
        self.messages: List = []
        self._changed = threading.Condition()
        self._sub = rospy.Subscriber(topic, msg_type, self._on_message, queue_size=50)

    def _on_message(self, msg) -> None:
        with self._changed:
            self.messages.append(msg)
            self._changed.notify_all()

    def wait_for(self, condition: Callable, timeout: float, count: int = 1) -> List:
        """Wait until ``count`` messages in a row after now satisfy ``condition``; return them."""
        with self._changed:
            start = len(self.messages)

            def satisfied() -> bool:
                recent = self.messages[start:]
                run = 0
                for msg in recent:
                    run = run + 1 if condition(msg) else 0
                return run >= count

            assert self._changed.wait_for(satisfied, timeout), "no %d matching messages in %.0f s (last: %s)" % (
                count,
                timeout,
                self.messages[-1:] if self.messages else "none",
            )
            return self.messages[-count:]


class Graph(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("graph")
        cls.limit = rospy.get_param("~wait_limit")
        cls.output = Recorder("cmd_vel_out", Twist)
        cls.diagnostics = Recorder("/diagnostics", DiagnosticArray)
        cls.publishers = {name: rospy.Publisher(name + "_vel", Twist, queue_size=1) for name in ("low", "high")}
        cls.stop = rospy.Publisher("stop", Bool, queue_size=1, latch=True)
        cls.speeds: Dict[str, float] = {}
        cls.timer = rospy.Timer(rospy.Duration(0.05), cls.publish_inputs)

    @classmethod
    def tearDownClass(cls) -> None:
        cls.timer.shutdown()
        cls.timer.join()

    @classmethod
    def publish_inputs(cls, _event) -> None:
        for name, speed in list(cls.speeds.items()):
            twist = Twist()
            twist.linear.x = speed
            cls.publishers[name].publish(twist)

    def status(self) -> Dict[str, str]:
        """The key-value pairs of the next twist_mux status."""

        def ours(array: DiagnosticArray) -> bool:
            return any(s.name == STATUS_NAME for s in array.status)

        array = self.diagnostics.wait_for(ours, self.limit)[0]
        status = [s for s in array.status if s.name == STATUS_NAME][0]
        self.assertEqual((status.level, status.message, status.hardware_id), (DiagnosticStatus.OK, "ok", "none"))
        return {pair.key: pair.value for pair in status.values}

    def test_priorities_timeouts_and_the_lock(self) -> None:
        self.speeds["low"] = LOW
        self.output.wait_for(lambda t: t.linear.x == LOW, self.limit)
        # both publish: only the higher passes, every time
        self.speeds["high"] = HIGH
        self.output.wait_for(lambda t: t.linear.x == HIGH, self.limit, count=20)
        # the higher stops: once it has timed out, the lower passes again
        del self.speeds["high"]
        self.output.wait_for(lambda t: t.linear.x == LOW, self.limit, count=5)
        # stop (priority 15) masks low (10) but not high (20)
        self.stop.publish(Bool(data=True))
        self.speeds["high"] = HIGH
        self.output.wait_for(lambda t: t.linear.x == HIGH, self.limit, count=20)
        values = self.status()
        self.assertEqual(values["current priority"], "15")
        self.assertEqual(values["lock stop"], " locked (listening to stop @ 0.000000s with priority #15)")
        self.assertEqual(values["velocity low"], " masked (listening to low_vel @ 0.300000s with priority #10)")
        self.assertEqual(values["velocity high"], " unmasked (listening to high_vel @ 0.300000s with priority #20)")
        self.assertEqual((values["loop time in [sec]"], values["data age in [sec]"]), ("0", "0"))
        # the lock lifted and high gone: low passes again
        del self.speeds["high"]
        self.stop.publish(Bool(data=False))
        self.output.wait_for(lambda t: t.linear.x == LOW, self.limit, count=5)
        self.assertEqual(self.status()["current priority"], "0")


if __name__ == "__main__":
    rostest.rosrun("twist_mux", "graph", Graph)
