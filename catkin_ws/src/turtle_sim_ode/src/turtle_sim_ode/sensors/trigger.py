"""When a triggered camera (gazebo_plugins' GazeboRosTriggeredCamera) takes its frames and when it sends them, in sim
time only, so that a frame reaches subscribers at the same sim time however long its rendering takes.

In Gazebo a trigger message counts one up (TriggerCamera); before each pass of the render loop a count above zero
enables the camera sensor (PreRender), which renders at most once per sim time (Sensor::Update returns while the
scene's sim time is not past the last update) and sends the frame from the render loop as soon as it is rendered,
stamped with the scene's sim time; each frame counts one down (OnNewFrame). The render loop runs beside the physics,
so a frame arrives a rendering's time after its stamp. Here a frame is rendered at the first step after its trigger
(the picture and stamp of that step, at most one a step) and held for TRIGGERED_FRAME_DELAY_S of sim time."""
from __future__ import annotations

import threading
from collections import deque
from typing import Deque, Generic, List, Tuple, TypeVar

# Sim time from a triggered frame's stamp to its sending: a rendering's time in Gazebo's render loop, fixed here.
# gazebo_plugins' triggered_camera test (cameraSubscribeTest) sends two triggers one /clock tick (10 ms) apart, looks
# for frames two ticks after the first trigger and then every 100 ms, and wants both frames at one look: with 50 ms
# the first frame goes out 30 ms of sim time after that first look at the earliest, and the second before the next
# look unless its trigger reached the simulator over 60 ms late.
TRIGGERED_FRAME_DELAY_S = 0.05

Payload = TypeVar("Payload")


class TriggeredFrames(Generic[Payload]):
    """Triggers counted (``trigger``, from any thread); at each step ``take`` uses one up if any (render then, and
    ``hold`` the frame); ``due`` gives the frames whose delay is over, oldest first."""

    def __init__(self, delay: float = TRIGGERED_FRAME_DELAY_S) -> None:
        self.delay = delay
        self._lock = threading.Lock()
        self._triggers = 0
        self._held: Deque[Tuple[float, Payload]] = deque()  # (sim time taken, frame)

    def trigger(self) -> None:
        with self._lock:
            self._triggers += 1

    def take(self) -> bool:
        """At a step: whether a trigger waits (then one is used up and a frame is to be rendered now)."""
        with self._lock:
            if not self._triggers:
                return False
            self._triggers -= 1
            return True

    def hold(self, taken: float, frame: Payload) -> None:
        """The frame rendered at sim time ``taken`` (after the frames held before it)."""
        self._held.append((taken, frame))

    def due(self, now: float) -> List[Payload]:
        """The held frames to send at sim time ``now`` (their delay over; 1e-9 s of rounding), oldest first."""
        sent = []
        while self._held and self._held[0][0] + self.delay <= now + 1e-9:
            sent.append(self._held.popleft()[1])
        return sent

    def clear(self) -> None:
        """Sim time went back (reset_simulation): the held frames of the old time are dropped."""
        self._held.clear()
