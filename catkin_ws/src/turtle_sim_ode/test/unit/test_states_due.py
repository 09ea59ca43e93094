"""GazeboApi.states_due (issue #33): the unpaced loop stops for model_states and link_states only while someone
listens to one of them; a subscriber that comes is served from the next step on (the due time already passed)."""
from __future__ import annotations

import math
import types

from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.ros.gazebo_api import GazeboApi


def publisher(subscribers: int) -> types.SimpleNamespace:
    """What wire.heard reads of a rospy Publisher: its topic's connections."""
    return types.SimpleNamespace(impl=types.SimpleNamespace(connections=[object()] * subscribers))


def api(model_subscribers: int, link_subscribers: int, next_states_time: float) -> GazeboApi:
    gazebo = GazeboApi.__new__(GazeboApi)  # the state topics alone, without a master
    gazebo._model_states_pub = publisher(model_subscribers)
    gazebo._link_states_pub = publisher(link_subscribers)
    gazebo.next_states_time = next_states_time
    return gazebo


@settings(database=None)  # as this package's newer tests: no replay of saved examples (Debian's 6.67)
@given(st.integers(0, 3), st.integers(0, 3), st.floats(0.0, 1e6, allow_nan=False))
def test_due_while_someone_listens_else_never(model_subscribers: int, link_subscribers: int, due: float) -> None:
    expected = due if model_subscribers or link_subscribers else math.inf
    assert api(model_subscribers, link_subscribers, due).states_due() == expected


def test_a_closed_topic_is_not_listened_to() -> None:
    gazebo = api(0, 0, 1.0)
    gazebo._model_states_pub = types.SimpleNamespace(impl=None)  # rospy sets impl None once it closed the topic
    assert gazebo.states_due() == math.inf
