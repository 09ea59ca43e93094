"""Gazebo's spawn services (spawn_urdf_model, spawn_sdf_model) on a Simulation: the request checked outside the world
lock, the model and its ROS side added under it, all or nothing; how a spawn's warnings are shown and its plugin
topics checked."""
from __future__ import annotations

import threading
from typing import Callable, Dict, List

import rosgraph
import rospy

from turtle_sim_ode.models.meshes import load_meshes, read_visual_meshes
from turtle_sim_ode.models.sdf import model_format, parse_sdf_model
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.ros.msg_values import quaternion_of, xyz
from turtle_sim_ode.ros.names import legal_base_name, legal_name, shown
from turtle_sim_ode.ros.throttle import logwarn_every
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.values import WorldError

# The most rays (laser samples) one model may cast per scan: each costs ~4 us under the world lock and ~600 bytes.
MAX_RAYS_PER_MODEL = 20000
# The longest model name a spawn accepts (characters): it prefixes topic names.
MAX_NAME_CHARS = 255
# A spawn answer lists at most this many warnings; the rest are counted.
MAX_SHOWN_WARNINGS = 10


class ModelSpawner:
    """The handler of both spawn services (a SpawnModel request and response)."""

    def __init__(
        self,
        sim: Simulation,
        lock: threading.Lock,
        on_spawn: Callable[[str, str, Callable[[str, type], None]], None],
        on_delete: Callable[[str], None],
    ) -> None:
        """``on_spawn(name, robot_namespace, check_topic)`` adds a spawned model's ROS interfaces (all or nothing),
        ``on_delete(name)`` removes them."""
        self._sim = sim
        self._lock = lock
        self._on_spawn = on_spawn
        self._on_delete = on_delete

    def __call__(self, request, response) -> None:
        """Called without the world lock: the text is checked outside it, so that a large or malformed model is
        refused without holding up the simulation; the parsed model, with its sensor and plugin blocks, is spawned under
        it. All or nothing: a model whose ROS side cannot be made (a topic in use with another type, a bad topic
        name, too many rays) is removed again."""
        name = request.model_name
        if not name:
            raise WorldError("model name is empty")
        # Both end up in the names of the model's plugin topics (a name the master refuses hangs the registration).
        if len(name) > MAX_NAME_CHARS:
            raise WorldError("model name %r is longer than %d characters" % (shown(name), MAX_NAME_CHARS))
        if not legal_base_name(name):
            raise WorldError(
                "model name %r is not a legal ROS name (an ASCII letter, then ASCII letters, digits or '_'): its "
                "plugins' topics are named after it" % shown(name)
            )
        if not legal_name(request.robot_namespace):
            raise WorldError(
                "robot_namespace %r of model '%s' is not a legal ROS namespace (ASCII letters, digits, '_' and '/')"
                % (shown(request.robot_namespace), name)
            )
        if not request.model_xml.strip():
            raise WorldError("model_xml of '%s' is empty" % name)
        xml_format = model_format(request.model_xml)
        if xml_format == "unknown":
            raise WorldError("model_xml of '%s' is neither URDF (<robot>) nor SDF (<sdf> or <model>)" % name)
        robot = (parse_urdf if xml_format == "urdf" else parse_sdf_model)(request.model_xml)
        initial_pose = (xyz(request.initial_pose.position), quaternion_of(request.initial_pose))
        check_topic = TopicTypes(name, known_topic_types())
        # Mesh files are read and checked before the world lock is taken: a large or bad one never holds up the
        # clock (only the trimesh is built under the lock).
        load_meshes(robot, self._sim.resources)
        with self._lock:
            watched = self._sim.models_seen_by_cameras(robot)
            known = self._sim.scene.known_files()
        visual_files = read_visual_meshes(watched, self._sim.resources, known)
        with self._lock:
            self._sim.scene.add_files(visual_files)
            warnings = self._sim.spawn_model(name, robot, initial_pose, request.reference_frame)
            try:  # the model's ROS side, refused over the ray limit or for a topic (see SimulatorNode.add_interface)
                self._on_spawn(name, request.robot_namespace, check_topic)
            except Exception as error:  # the ROS side could not be made: nothing of the model stays
                self._on_delete(name)
                self._sim.delete(name)
                if isinstance(error, (WorldError, ModelError)):
                    raise
                raise WorldError("model '%s' was not spawned: %s: %s" % (name, type(error).__name__, error)) from None
        warnings = summarise(warnings)
        response.status_message = "SpawnModel: Successfully spawned entity" + (
            " (warnings: %s)" % "; ".join(warnings) if warnings else ""
        )
        if warnings:
            rospy.logwarn("spawn %s: %s", name, "; ".join(warnings))
        rospy.loginfo("spawned model [%s]", name)


def summarise(warnings: List[str]) -> List[str]:
    """Spawn warnings as an answer and the log show them: at most MAX_SHOWN_WARNINGS, each shortened, then how many
    more there were."""
    summary = [shown(w, 300) for w in warnings[:MAX_SHOWN_WARNINGS]]
    if len(warnings) > MAX_SHOWN_WARNINGS:
        summary.append("and %d more warnings" % (len(warnings) - MAX_SHOWN_WARNINGS))
    return summary


def known_topic_types() -> Dict[str, str]:
    """Every topic some node publishes or subscribes to now, with its type (the master keeps the types of topics
    no node uses any more: those are left out); empty if the master does not answer."""
    try:
        master = rosgraph.Master(rospy.get_name())
        publishers, subscribers, _ = master.getSystemState()
        in_use = {topic for topic, nodes in list(publishers) + list(subscribers) if nodes}
        return {topic: kind for topic, kind in master.getTopicTypes() if topic in in_use}
    except Exception as error:  # noqa: BLE001 - a spawn must not fail for a lookup: its own topics are still checked
        logwarn_every(10.0, "topic_types", "cannot ask the master for topic types: %s" % error)
        return {}


class TopicTypes:
    """check_topic of a spawn: refuse a plugin topic that is not a legal ROS name, or that another node (or this
    one, or another plugin of the same model) uses with another message type."""

    def __init__(self, model: str, known: Dict[str, str]) -> None:
        self._model = model
        self._known = known
        self._owner: Dict[str, str] = {}

    def __call__(self, topic: str, msg_type: type) -> None:
        if not topic or not legal_name(topic):
            raise WorldError(
                "model '%s': plugin topic %r is not a legal ROS name (ASCII letters, digits, '_' and '/')"
                % (self._model, shown(topic))
            )
        resolved = rospy.resolve_name(topic)
        wanted = msg_type._type
        existing = self._known.get(resolved)
        if existing is not None and existing != wanted:
            owner = self._owner.get(resolved, "already in use")
            raise WorldError(
                "model '%s': topic %s is %s with type %s; the model's plugin would use it with type %s (set another "
                "topicName or robotNamespace)" % (self._model, resolved, owner, existing, wanted)
            )
        if existing is None:
            self._known[resolved] = wanted
            self._owner[resolved] = "also used by another of the model's plugins"
