"""ROS names as the simulator accepts them, and names and lists as its answers show them (ROS-free)."""
from __future__ import annotations

from typing import Iterable

from rosgraph.names import is_legal_base_name, is_legal_name

# A name shown in a status_message or log line keeps this many characters.
SHOWN_NAME_CHARS = 80
# No status_message is longer than this (characters).
MAX_STATUS_CHARS = 4000


def legal_base_name(name: str) -> bool:
    """A ROS base name: an ASCII letter, then ASCII letters, digits or '_' (rosgraph's check takes any Unicode
    letter, which the master and other client libraries refuse)."""
    return name.isascii() and is_legal_base_name(name)


def legal_name(name: str) -> bool:
    """A ROS graph name (namespace or topic): ASCII letters, digits, '_' and '/', as rosgraph checks it."""
    return name.isascii() and is_legal_name(name)


def shown(name: str, limit: int = SHOWN_NAME_CHARS) -> str:
    """``name`` as an answer shows it: the first ``limit`` characters and the length of a longer one."""
    if len(name) <= limit:
        return name
    return f"{name[:limit]}... ({len(name)} characters)"


def shorten_names_in(message: str, names: Iterable[str], limit: int = MAX_STATUS_CHARS) -> str:
    """``message`` with every long name of ``names`` in it shortened (see ``shown``), then cut to ``limit``
    characters."""
    for name in sorted({n for n in names if len(n) > SHOWN_NAME_CHARS}, key=len, reverse=True):
        message = message.replace(repr(name)[1:-1], shown(name)).replace(name, shown(name))
    if len(message) > limit:
        message = f"{message[:limit]}... ({len(message)} characters)"
    return message
