"""Filters. Semantics from rqt_console (melodic-devel = noetic) src/rqt_console/filters/: message_filter.py
(substring, or a regex matched with .* around unless anchored), filter_collection.py (any enabled filter that has
something set; the default when none has), severity/node/topic_filter.py (membership)."""
import pytest

from rqt_console.filters import (
    FilterCollection,
    LocationFilter,
    MessageFilter,
    NodeFilter,
    SeverityFilter,
    TopicFilter,
)
from rqt_console.log_record import ERROR, INFO, WARN, LogRecord

WALL = LogRecord(
    "Oh no! I hit the wall! (Clamping from [x=11.1, y=5.5])",
    WARN,
    "/turtlesim",
    (1700000000, 5),
    ("/rosout", "/turtle1/pose"),
    "world.py:update:80",
)
HELLO = LogRecord("hello world 42", INFO, "/talker", (1700000001, 0), ("/chatter", "/rosout"), "talker.py:talk:20")


def test_message_text_is_a_case_sensitive_substring():
    assert MessageFilter("hit the wall").matches(WALL)
    assert not MessageFilter("Hit the wall").matches(WALL)
    assert not MessageFilter("").matches(WALL) and not MessageFilter("").has_filter()


@pytest.mark.parametrize(
    "pattern, expected",
    [("wall", True), ("^Oh no", True), ("^no", False), (r"\)$", True), ("x=[0-9.]+", True), ("^hello", False)],
)
def test_message_regex_is_found_anywhere_unless_anchored(pattern, expected):
    assert MessageFilter(pattern, regex=True).matches(WALL) is expected


def test_an_invalid_regex_matches_nothing_and_says_why():
    broken = MessageFilter("([", regex=True)
    assert not broken.matches(WALL) and "invalid regular expression" in broken.error
    broken.set_text("(wall)")
    assert broken.matches(WALL) and broken.error == ""


def test_selections():
    assert SeverityFilter({WARN, ERROR}).matches(WALL) and not SeverityFilter({WARN}).matches(HELLO)
    assert NodeFilter({"/talker"}).matches(HELLO) and not NodeFilter({"/talker"}).matches(WALL)
    assert TopicFilter({"/turtle1/pose"}).matches(WALL) and not TopicFilter({"/turtle1/pose"}).matches(HELLO)
    assert LocationFilter("talker.py").matches(HELLO)


def test_disabled_filters_match_nothing():
    wall = MessageFilter("wall")
    wall.enabled = False
    assert not wall.matches(WALL)


def test_collection_any_active_filter_or_the_default():
    collection = FilterCollection()
    assert collection.matches(WALL) is False and collection.matches(WALL, default=True) is True
    collection.filters.append(MessageFilter(""))  # nothing set: not active
    assert collection.matches(WALL, default=True) is True
    collection.filters += [MessageFilter("nothing like it"), NodeFilter({"/turtlesim"})]
    assert collection.matches(WALL, default=True) and not collection.matches(HELLO, default=True)
