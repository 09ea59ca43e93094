"""What every publisher of the simulator's plugins shares: sim-time stamps, topic names in a model's namespace, a
schedule of its own in sim time (Periodic), and advertising that checks each topic first and keeps what it opened, so
a model's spawn can be refused or undone whole (Advertising)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, List, Optional

import rospy

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.ros.settings import SimulatorSettings
from turtle_sim_ode.ros.wire import PackedPublisher, stamp_parts
from turtle_sim_ode.world.plugins.p3d import find_body
from turtle_sim_ode.world.simulation import Simulation

_new_time = rospy.Time.__new__


def ros_time(secs: int, nsecs: int) -> rospy.Time:
    """rospy.Time(secs, nsecs) of a stamp already in range (0 <= nsecs < 1e9), without the constructor's checks and
    normalisation: the same object for a sixth of the cost (the node makes one at every step that publishes)."""
    stamp = _new_time(rospy.Time)
    stamp.secs, stamp.nsecs = secs, nsecs
    return stamp


def sim_stamp(seconds: float) -> rospy.Time:
    return ros_time(*stamp_parts(seconds))


def topic_prefix(namespace: str) -> str:
    """A model's robot namespace prefixes its plugin topics, as gazebo_ros plugins do."""
    namespace = namespace.strip("/")
    return namespace + "/" if namespace else ""


def plugin_topic(namespace: str, topic: str) -> str:
    """A plugin's topic in the model's namespace; an absolute topic name stays as it is."""
    return topic if topic.startswith("/") else topic_prefix(namespace) + topic


class Periodic:
    """A publisher with its own rate in sim time."""

    def __init__(self, period: float) -> None:
        self._period = period
        self._next = 0.0

    @property
    def next_due(self) -> float:
        """Sim time from which ``publish_due`` publishes (less 1e-9 s of rounding)."""
        return self._next

    def restart(self, now: float) -> None:
        self._next = now

    def publish_due(self, now: float, stamp: rospy.Time) -> None:
        """Publish if due at sim time ``now``; ``stamp`` is ``sim_stamp(now)``, made once for all that fall due."""
        if now >= self._next - 1e-9:
            self._next = max(self._next + self._period, now)
            self.publish(stamp, now)

    def publish(self, stamp: rospy.Time, now: float) -> None:
        raise NotImplementedError

    def close(self) -> None:
        raise NotImplementedError


# Called with each topic name and message class before a model's plugin advertises or subscribes to it; raises
# (WorldError) to refuse the model.
TopicCheck = Callable[[str, type], None]


class Advertising:
    """The topics one model_interfaces call opens: each checked first, all released if the call fails."""

    check: Optional[TopicCheck] = None
    opened: List[Any] = []


def _opened(handle: Any) -> Any:
    Advertising.opened.append(handle)
    return handle


def packed_publisher(topic: str, msg_type: type) -> PackedPublisher:
    if Advertising.check is not None:
        Advertising.check(topic, msg_type)
    return _opened(PackedPublisher(topic, msg_type))


def publisher(topic: str, msg_type: type, queue_size: int) -> rospy.Publisher:
    if Advertising.check is not None:
        Advertising.check(topic, msg_type)
    return _opened(rospy.Publisher(topic, msg_type, queue_size=queue_size))


def subscriber(topic: str, msg_type: type, callback: Callable[[Any], None], queue_size: int) -> rospy.Subscriber:
    if Advertising.check is not None:
        Advertising.check(topic, msg_type)
    return _opened(rospy.Subscriber(topic, msg_type, callback, queue_size=queue_size))


@dataclass
class ModelContext:
    """What a plugin's ROS adapter (ros.plugins) is made with: the model's name, the simulation (the model is
    ``sim.models[name]``), the node's settings and tf broadcaster, the spawn's robot namespace ("": none), and
    ``pace_from_now``: called in a step whose wall time sim time should not catch up afterwards (work that Gazebo
    does beside its physics, such as rendering a triggered frame), so the run loop paces on from the step's end."""

    name: str
    sim: Simulation
    settings: SimulatorSettings
    tf_broadcaster: PackedPublisher
    namespace: str
    pace_from_now: Callable[[], None] = lambda: None

    @property
    def model(self) -> BuiltModel:
        return self.sim.models[self.name]

    def body_link(self, body: str, plugin: str, outcome: str = "not published") -> Optional[str]:
        """The link a plugin's ``bodyName`` names ('model::link' scoped too; "" the model's canonical link), or
        None after a warning that names the plugin and what follows (``outcome``)."""
        model = self.model
        link = find_body(list(model.links), body) if body else model.root_link
        if link is None:
            rospy.logwarn("model %s: %s bodyName [%s] is not a link: %s", self.name, plugin, body, outcome)
        return link
