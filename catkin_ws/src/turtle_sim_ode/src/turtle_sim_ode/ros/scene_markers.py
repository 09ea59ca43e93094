"""/gazebo/scene_markers (visualization_msgs/MarkerArray): the world's models as Gazebo's client draws them, for the
viewer (rviz's MarkerArray display, which keeps each marker until it is deleted).

Published only while someone listens, from a thread of its own at SCENE_RATE_HZ of wall time, paused or not (a
set_model_state while paused shows at once): a new listener first gets the whole scene (DELETEALL, then every visual),
then every listener gets only what changed: the visuals of links that moved, models spawned (ADD), models deleted
(DELETE of each of their markers). Markers are in frame `world`: namespace the model's name, id the visual's index in
it. The world lock is held only to read link poses; messages are built and sent outside it."""
from __future__ import annotations

import threading
import time
from typing import Dict, List, Tuple

import rospy
from geometry_msgs.msg import Point, Pose, Quaternion, Vector3
from std_msgs.msg import ColorRGBA, Header
from visualization_msgs.msg import Marker, MarkerArray

from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.viewer_scene import OWN_COLOURS, Placed, SceneTracker, SceneUpdate, SceneVisual

TOPIC = "/gazebo/scene_markers"
FRAME = "world"
SCENE_RATE_HZ = 30.0
# How often a scene nobody listens to checks for a listener.
IDLE_CHECK_S = 0.2
MARKER_TYPES = {"box": Marker.CUBE, "cylinder": Marker.CYLINDER, "sphere": Marker.SPHERE, "mesh": Marker.MESH_RESOURCE}


def marker_of(model: str, index: int, visual: SceneVisual) -> Marker:
    """The ADD marker of a visual, pose not yet set."""
    marker = Marker(header=Header(frame_id=FRAME), ns=model, id=index, type=MARKER_TYPES[visual.shape])
    marker.action = Marker.ADD
    marker.scale = Vector3(*visual.size)
    marker.color = ColorRGBA(*visual.rgba)
    if visual.shape == "mesh":
        marker.mesh_resource = "file://" + visual.mesh_path
        # The file's own materials only where the visual has none: rviz draws embedded materials tinted by any
        # other colour (a second pass at half opacity), where Gazebo replaces them with the visual's material.
        marker.mesh_use_embedded_materials = visual.rgba == OWN_COLOURS
    return marker


def deletion(model: str, index: int) -> Marker:
    return Marker(header=Header(frame_id=FRAME), ns=model, id=index, action=Marker.DELETE)


class _Newcomers(rospy.SubscribeListener):
    def __init__(self, scene: "SceneMarkers") -> None:
        super().__init__()
        self.scene = scene

    def peer_subscribe(self, topic_name, topic_publish, peer_publish):  # type: ignore[no-untyped-def]
        peer_publish(self.scene.whole_scene())


class SceneMarkers:
    """Publishes ``sim``'s scene (models read under ``lock``) while the topic has subscribers."""

    def __init__(self, sim: Simulation, lock: threading.Lock) -> None:
        self.sim = sim
        self.lock = lock
        self.tracker = SceneTracker(sim.resources)
        self._markers: Dict[Tuple[str, int], Marker] = {}  # by (model, index), reused: only poses change
        self._state_lock = threading.Lock()  # the tracker and markers: this thread and a newcomer's
        self._stop = threading.Event()
        self.publisher = rospy.Publisher(TOPIC, MarkerArray, queue_size=2, subscriber_listener=_Newcomers(self))
        self._thread = threading.Thread(target=self._run, name="scene_markers", daemon=True)
        self._thread.start()

    def close(self) -> None:
        self._stop.set()
        self._thread.join(1.0)
        self.publisher.unregister()

    def _placed(self, model: str, placed: List[Placed], fresh: bool) -> List[Marker]:
        found = []
        for index, visual, (position, (w, x, y, z)) in placed:
            marker = None if fresh else self._markers.get((model, index))
            if marker is None:
                marker = self._markers[(model, index)] = marker_of(model, index, visual)
            marker.pose = Pose(Point(*position), Quaternion(x, y, z, w))
            found.append(marker)
        return found

    def apply(self, update: SceneUpdate) -> MarkerArray:
        """The markers that tell a viewer ``update`` (call with the state lock)."""
        markers: List[Marker] = []
        for model, count in update.removed.items():
            for index in range(count):
                self._markers.pop((model, index), None)
                markers.append(deletion(model, index))
        for model, placed in update.added.items():
            markers += self._placed(model, placed, True)
        for model, placed in update.moved.items():
            markers += self._placed(model, placed, False)
        for warning in update.warnings:
            rospy.logwarn("scene: %s", warning)
        return MarkerArray(markers)

    def whole_scene(self) -> MarkerArray:
        """Everything as last sent, after a DELETEALL (what a new viewer may have kept from an earlier world)."""
        with self._state_lock:
            markers = [Marker(header=Header(frame_id=FRAME), action=Marker.DELETEALL)]
            for model, placed in self.tracker.everything().items():
                markers += self._placed(model, placed, False)
            return MarkerArray(markers)

    def publish_changes(self) -> None:
        with self.lock:
            snapshot = self.tracker.read_poses(self.sim.models, self.sim.physics.has_own_ground)
        with self._state_lock:
            self.tracker.meshes.resources = self.sim.resources
            message = self.apply(self.tracker.update(snapshot))
        if message.markers:
            self.publisher.publish(message)

    def _run(self) -> None:
        period = 1.0 / SCENE_RATE_HZ
        due = time.monotonic()
        while not self._stop.is_set() and not rospy.is_shutdown():
            if self.publisher.get_num_connections() == 0:
                self._stop.wait(IDLE_CHECK_S)
                due = time.monotonic()
                continue
            try:
                self.publish_changes()
            except Exception as error:  # the viewer's scene never ends the simulator
                rospy.logwarn_throttle(10.0, "scene: not published: %s: %s" % (type(error).__name__, error))
            # On a schedule, not a pause after the work: waiting for the world lock and the GIL does not slow the
            # rate; a tick late by more than a period is not made up.
            now = time.monotonic()
            due = max(due + period, now - period)
            self._stop.wait(max(0.0, due - now))
