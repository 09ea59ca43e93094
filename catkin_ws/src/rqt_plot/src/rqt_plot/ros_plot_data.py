"""The ROS side of rqt_plot: the master's published topics, and one subscriber per topic whose callback reads the
plotted fields into the DataWindow. Callbacks never touch a widget."""
from __future__ import annotations

import threading
from typing import Dict, List, Tuple

import roslib.message
import rospy

from .data_window import DataWindow
from .fields import FieldReader, plot_fields, split_topic


def load_message_class(type_name: str):
    return roslib.message.get_message_class(type_name)


def published_topic_types() -> Dict[str, str]:
    """{topic: type} of the master's published topics; {} when the master does not answer."""
    try:
        return dict(rospy.get_published_topics())
    except Exception as error:  # socket errors, master gone: the box simply offers nothing
        rospy.logwarn_throttle(10.0, "rqt_plot: no topic list from the master [%s]" % error)
        return {}


class TopicSubscriptions:
    """Curves fed from subscribers: x is header.stamp where the message has a header, else ROS time at receipt,
    both minus the start time."""

    def __init__(self, window: DataWindow, start_time: float) -> None:
        self._window = window
        self._start_time = start_time
        self._lock = threading.Lock()
        self._readers: Dict[str, List[Tuple[str, FieldReader]]] = {}  # topic -> curves read from it
        self._subscribers: Dict[str, rospy.Subscriber] = {}
        self.errors: Dict[str, str] = {}  # curve -> why its last value could not be read

    def add(self, curve: str, topic_types: Dict[str, str]) -> str:
        """Subscribes for one curve (a field path from plot_fields); returns '' or why it cannot be added."""
        found = split_topic(curve, topic_types)
        if found is None:
            return "topic of %s is not published" % curve
        topic, type_name, field = found
        message_class = load_message_class(type_name)
        if message_class is None:
            return "message type %s of %s is unknown (is its package built and sourced?)" % (type_name, topic)
        self._window.add(curve)
        with self._lock:
            self._readers.setdefault(topic, []).append((curve, FieldReader(field)))
        if topic not in self._subscribers:
            self._subscribers[topic] = rospy.Subscriber(
                topic, message_class, self._on_message, callback_args=topic, queue_size=100
            )
        return ""

    def remove(self, curve: str) -> None:
        for topic in list(self._readers):
            with self._lock:
                self._readers[topic] = [(name, reader) for name, reader in self._readers[topic] if name != curve]
                unused = not self._readers[topic]
                if unused:
                    del self._readers[topic]
            if unused:
                self._subscribers.pop(topic).unregister()
        self._window.remove(curve)
        self.errors.pop(curve, None)

    def curves(self) -> List[str]:
        with self._lock:
            return [curve for readers in self._readers.values() for curve, _ in readers]

    def shutdown(self) -> None:
        for subscriber in self._subscribers.values():
            subscriber.unregister()
        self._subscribers.clear()
        with self._lock:
            self._readers.clear()

    def _on_message(self, message, topic: str) -> None:
        header = getattr(message, "header", None) if getattr(message, "_has_header", False) else None
        x = (header.stamp.to_sec() if header is not None else rospy.get_time()) - self._start_time
        with self._lock:
            readers = list(self._readers.get(topic, ()))
        for curve, reader in readers:
            try:
                self._window.push(curve, x, reader(message))
            except (LookupError, TypeError, ValueError, AttributeError) as error:
                self.errors[curve] = str(error)
                rospy.logwarn_throttle(5.0, "rqt_plot: cannot read %s [%s]" % (curve, error))


def curves_for(path: str, topic_types: Dict[str, str]) -> Tuple[List[str], str]:
    """plot_fields with the classes of the ROS message packages on this system."""
    return plot_fields(path, topic_types, load_message_class)
