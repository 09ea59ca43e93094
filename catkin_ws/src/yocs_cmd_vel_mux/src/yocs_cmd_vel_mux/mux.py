"""The velocity multiplexer's rules without ROS: which input may drive the robot, and when it stops being active.

The rules are those of yujinrobot/yujin_ocs yocs_cmd_vel_mux (CmdVelMuxNodelet::cmdVelCallback, timerCallback,
CmdVelSubscribers::configure): a command is forwarded if no input is active, if its input is the active one, or
if its input's priority is higher than the active one's (it then becomes active); an input that has sent nothing
for its timeout stops being active, and so does the active one when no input at all has sent anything for twice
the longest timeout.
"""
from __future__ import annotations

from typing import Any, List, Mapping, NamedTuple, Optional, Sequence

IDLE = "idle"


class ConfigError(ValueError):
    """The subscribers list cannot be used; the message names the entry and the bad value."""


class Input(NamedTuple):
    name: str
    topic: str
    timeout: float
    priority: int
    short_desc: str = ""


def parse_inputs(subscribers: Any) -> List[Input]:
    """The `subscribers` list of a mux yaml file (name, topic, timeout, priority, optional short_desc)."""
    if not isinstance(subscribers, list) or not subscribers:
        raise ConfigError("subscribers: a non-empty list is needed, got [%r]" % (subscribers,))
    inputs = []
    for index, entry in enumerate(subscribers):
        if not isinstance(entry, Mapping):
            raise ConfigError("subscribers[%d]: a mapping is needed, got [%r]" % (index, entry))
        missing = [key for key in ("name", "topic", "timeout", "priority") if key not in entry]
        if missing:
            raise ConfigError("subscribers[%d]: %s missing" % (index, ", ".join(missing)))
        timeout, priority = entry["timeout"], entry["priority"]
        if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) or not 0 < timeout < float("inf"):
            raise ConfigError("subscribers[%d]: timeout must be a positive number, got [%r]" % (index, timeout))
        if isinstance(priority, bool) or not isinstance(priority, int) or priority < 0:
            raise ConfigError("subscribers[%d]: priority must be an unsigned integer, got [%r]" % (index, priority))
        inputs.append(
            Input(str(entry["name"]), str(entry["topic"]), float(timeout), priority, str(entry.get("short_desc", "")))
        )
    priorities = [i.priority for i in inputs]
    if len(set(priorities)) != len(priorities):
        raise ConfigError("subscribers: priorities must be unique, got %s" % priorities)
    return inputs


class CmdVelMux:
    """Feed it commands (command) and the time (expire); `active` is the active input's name or 'idle'."""

    def __init__(self, inputs: Sequence[Input]) -> None:
        self.inputs = list(inputs)
        self._allowed: Optional[int] = None
        self._last = [float("-inf")] * len(self.inputs)
        self._last_any = float("-inf")
        self.common_timeout = 2.0 * max(i.timeout for i in self.inputs)

    @property
    def active(self) -> str:
        return IDLE if self._allowed is None else self.inputs[self._allowed].name

    def command(self, index: int, now: float) -> bool:
        """A command arrived on input `index` at `now`: True if it is to be forwarded."""
        self.expire(now)  # a timed-out input must not block this command until the next timer tick
        self._last[index] = self._last_any = now
        allowed = self._allowed
        if allowed is None or allowed == index or self.inputs[index].priority > self.inputs[allowed].priority:
            self._allowed = index
            return True
        return False

    def expire(self, now: float) -> bool:
        """Release the active input if it has timed out (its own timeout, or nothing from anyone for twice the
        longest); True if it was released (the warning case of the common timeout is not told apart)."""
        if self._allowed is None:
            return False
        own = now - self._last[self._allowed] >= self.inputs[self._allowed].timeout
        if own or now - self._last_any >= self.common_timeout:
            self._allowed = None
            return True
        return False

    def reset(self) -> None:
        """Back to idle with no history (sim time jumped back)."""
        self._allowed = None
        self._last = [float("-inf")] * len(self.inputs)
        self._last_any = float("-inf")
