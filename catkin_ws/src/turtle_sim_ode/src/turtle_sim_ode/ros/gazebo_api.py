"""Gazebo classic's ROS API (gazebo_ros, Noetic) on a Simulation: the /gazebo/* services and topics with
gazebo_msgs types, so code written for Gazebo runs unchanged.

Logical failures answer success: false with a status_message, as gazebo_ros does; the service call itself
succeeds. Unlike gazebo_ros, spawning never waits on sim time (Gazebo's spawn hangs while paused or at /clock 0).
"""
from __future__ import annotations

import contextlib
import math
import threading
from typing import Callable, Dict, List, Sequence, Tuple

import rosgraph
import rospy
from gazebo_msgs import srv as gz
from gazebo_msgs.msg import LinkState, LinkStates, ModelState, ModelStates, ODEJointProperties, ODEPhysics
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from std_msgs.msg import ColorRGBA
from std_srvs.srv import Empty, EmptyResponse

from turtle_sim_ode.models.meshes import load_meshes, read_visual_meshes
from turtle_sim_ode.models.sdf import model_format, parse_sdf_model
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.ros.names import legal_base_name, legal_name, shorten_names_in, shown
from turtle_sim_ode.ros.pacing import pacing_problem
from turtle_sim_ode.ros.physics_reconfigure import PhysicsReconfigure
from turtle_sim_ode.ros.throttle import logwarn_every
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.values import WorldError

Vec3 = Tuple[float, float, float]
State = Tuple[Vec3, Tuple[float, float, float, float], Vec3, Vec3]
# The most rays (laser samples) one model may cast per scan: each costs ~4 us under the world lock and ~600 bytes.
MAX_RAYS_PER_MODEL = 20000
# The longest model name a spawn accepts (characters): it prefixes topic names.
MAX_NAME_CHARS = 255
# A spawn answer lists at most this many warnings; the rest are counted.
MAX_SHOWN_WARNINGS = 10


def xyz(vector) -> Vec3:
    return (vector.x, vector.y, vector.z)


def quaternion_of(pose: Pose) -> Tuple[float, float, float, float]:
    q = pose.orientation
    return (q.x, q.y, q.z, q.w)


def pose_msg(position: Sequence[float], quaternion: Sequence[float]) -> Pose:
    return Pose(Point(*position), Quaternion(*quaternion))


def rgba(colour: ColorRGBA) -> Tuple[float, float, float, float]:
    return (colour.r, colour.g, colour.b, colour.a)


def twist_msg(linear: Sequence[float], angular: Sequence[float]) -> Twist:
    return Twist(Vector3(*linear), Vector3(*angular))


class GazeboApi:
    """Registers the /gazebo services and topics of the node it is given (a node named `gazebo`)."""

    def __init__(
        self,
        sim: Simulation,
        lock: threading.Lock,
        on_spawn: Callable[[str, str], None],
        on_delete: Callable[[str], None],
        pause: Callable[[bool], None],
        is_paused: Callable[[], bool],
        states_rate: float,
        pub_clock_frequency: float,
        on_time_change: Callable[[str], None],
    ) -> None:
        """``on_spawn(name, robot_namespace, check_topic)`` adds a spawned model's ROS interfaces (all or nothing),
        ``on_delete(name)`` removes them; ``on_time_change(what)`` follows set_physics_properties, reset_world and
        reset_simulation (under the lock)."""
        self._sim = sim
        self._lock = lock
        self._on_spawn = on_spawn
        self._on_delete = on_delete
        self._pause = pause
        self._is_paused = is_paused
        self._pub_clock_frequency = pub_clock_frequency
        self._on_time_change = on_time_change
        self._request_count = 0
        services = [
            ("spawn_urdf_model", gz.SpawnModel, self._spawn),
            ("spawn_sdf_model", gz.SpawnModel, self._spawn),
            ("delete_model", gz.DeleteModel, self._delete_model),
            ("get_model_state", gz.GetModelState, self._get_model_state),
            ("set_model_state", gz.SetModelState, self._set_model_state),
            ("get_model_properties", gz.GetModelProperties, self._get_model_properties),
            ("get_world_properties", gz.GetWorldProperties, self._get_world_properties),
            ("get_link_state", gz.GetLinkState, self._get_link_state),
            ("set_link_state", gz.SetLinkState, self._set_link_state),
            ("get_link_properties", gz.GetLinkProperties, self._get_link_properties),
            ("set_link_properties", gz.SetLinkProperties, self._set_link_properties),
            ("get_joint_properties", gz.GetJointProperties, self._get_joint_properties),
            ("set_joint_properties", gz.SetJointProperties, self._set_joint_properties),
            ("get_physics_properties", gz.GetPhysicsProperties, self._get_physics_properties),
            ("set_physics_properties", gz.SetPhysicsProperties, self._set_physics_properties),
            ("set_model_configuration", gz.SetModelConfiguration, self._set_model_configuration),
            ("apply_body_wrench", gz.ApplyBodyWrench, self._apply_body_wrench),
            ("clear_body_wrenches", gz.BodyRequest, self._clear_body_wrenches),
            ("apply_joint_effort", gz.ApplyJointEffort, self._apply_joint_effort),
            ("clear_joint_forces", gz.JointRequest, self._clear_joint_forces),
            ("delete_light", gz.DeleteLight, self._delete_light),
            ("get_light_properties", gz.GetLightProperties, self._get_light_properties),
            ("set_light_properties", gz.SetLightProperties, self._set_light_properties),
        ]
        serve = {
            name: self._answer(name, srv_type, handler, handler != self._spawn) for name, srv_type, handler in services
        }
        self._services = [rospy.Service("~" + name, srv_type, serve[name]) for name, srv_type, _ in services]
        self._services += [
            rospy.Service("~pause_physics", Empty, lambda _: self._empty(lambda: self._pause(True))),
            rospy.Service("~unpause_physics", Empty, lambda _: self._empty(lambda: self._pause(False))),
            rospy.Service("~reset_world", Empty, lambda _: self._empty(self._reset_world)),
            rospy.Service("~reset_simulation", Empty, lambda _: self._empty(self._reset_simulation)),
        ]
        self._model_states_pub = rospy.Publisher("~model_states", ModelStates, queue_size=1)
        self._link_states_pub = rospy.Publisher("~link_states", LinkStates, queue_size=1)
        self._subscribers = [
            rospy.Subscriber("~set_model_state", ModelState, self._on_set_model_state, queue_size=10),
            rospy.Subscriber("~set_link_state", LinkState, self._on_set_link_state, queue_size=10),
        ]
        self.states_period = 1.0 / states_rate
        self.next_states_time = 0.0
        # As gazebo_ros: offered once the physics services are (physicsReconfigureThread waits for them).
        self.physics_reconfigure = PhysicsReconfigure(serve["get_physics_properties"], serve["set_physics_properties"])

    # --- plumbing -------------------------------------------------------------------------------------------
    def _answer(self, name: str, srv_type, handler, locked: bool = True):
        """Wrap a handler: it fills the response, under the world lock if ``locked`` (else it takes the lock itself);
        a logical error becomes success: false with the message, logged once as a warning."""
        response_class = srv_type._response_class

        def serve(request):
            response = response_class()
            # BodyRequest and JointRequest have empty responses: their failures can only be logged.
            reports = hasattr(response, "success")
            try:
                with self._lock if locked else contextlib.nullcontext():
                    handler(request, response)
                if reports:
                    response.success = True
            except Exception as error:  # every input is answered; what no check foresaw is named by its type
                # Names in a request are the caller's: a long one is shortened wherever the answer shows it.
                names = [value for value in request_strings(request) if len(value) > 80]
                text = error if isinstance(error, ValueError) else "%s: %s" % (type(error).__name__, error)
                message = shorten_names_in("%s: %s" % (name, text), names)
                rospy.logwarn("/gazebo/%s", message)
                if reports:
                    response.success = False
                    response.status_message = message
            return response

        return serve

    def _empty(self, action: Callable[[], None]) -> EmptyResponse:
        with self._lock:
            action()
        return EmptyResponse()

    # --- lights -------------------------------------------------------------------------------------------
    def _get_light_properties(self, request, response) -> None:
        light = self._sim.light_properties(request.light_name)
        response.diffuse = ColorRGBA(*light.diffuse)
        response.attenuation_constant = light.attenuation_constant
        response.attenuation_linear = light.attenuation_linear
        response.attenuation_quadratic = light.attenuation_quadratic

    def _set_light_properties(self, request, response) -> None:
        self._sim.set_light_properties(
            request.light_name,
            request.cast_shadows,
            rgba(request.diffuse),
            rgba(request.specular),
            (request.attenuation_constant, request.attenuation_linear, request.attenuation_quadratic),
            xyz(request.direction),
            xyz(request.pose.position),
            quaternion_of(request.pose),
        )

    def _delete_light(self, request, response) -> None:
        self._sim.delete_light(request.light_name)
        response.status_message = "DeleteLight: %s successfully deleted" % request.light_name

    # --- models ---------------------------------------------------------------------------------------------
    def _spawn(self, request, response) -> None:
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

    def _delete_model(self, request, response) -> None:
        self._sim.delete(request.model_name)
        self._on_delete(request.model_name)
        response.status_message = "DeleteModel: successfully deleted model"

    def _get_model_state(self, request, response) -> None:
        position, quaternion, linear, angular = self._sim.get_model_state(
            request.model_name, request.relative_entity_name
        )
        self._request_count += 1
        response.header.seq = self._request_count
        response.header.stamp = rospy.Time.from_sec(self._sim.sim_time)
        response.header.frame_id = request.relative_entity_name
        response.pose = pose_msg(position, quaternion)
        response.twist = twist_msg(linear, angular)
        response.status_message = "GetModelState: got properties"

    def _set_model_state(self, request, response) -> None:
        self._apply_model_state(request.model_state)
        response.status_message = "SetModelState: set model state done"

    def _apply_model_state(self, state: ModelState) -> None:
        self._sim.set_model_state(
            state.model_name,
            xyz(state.pose.position),
            quaternion_of(state.pose),
            xyz(state.twist.linear),
            xyz(state.twist.angular),
            state.reference_frame,
        )

    def _on_set_model_state(self, state: ModelState) -> None:
        try:
            with self._lock:
                self._apply_model_state(state)
        except (WorldError, ValueError, ArithmeticError) as error:  # numbers too large for a step: a warning too
            logwarn_every(5.0, "set_model_state", "/gazebo/set_model_state: %s" % error)

    def _get_model_properties(self, request, response) -> None:
        for field, value in self._sim.model_properties(request.model_name).items():
            setattr(response, field, value)
        response.status_message = "GetModelProperties: got properties"

    def _get_world_properties(self, _request, response) -> None:
        for field, value in self._sim.world_properties().items():
            setattr(response, field, value)
        response.status_message = "GetWorldProperties: got properties"

    # --- links ----------------------------------------------------------------------------------------------
    def _get_link_state(self, request, response) -> None:
        position, quaternion, linear, angular = self._sim.get_link_state(request.link_name, request.reference_frame)
        response.link_state = LinkState(
            request.link_name, pose_msg(position, quaternion), twist_msg(linear, angular), request.reference_frame
        )
        response.status_message = "GetLinkState: got state"

    def _set_link_state(self, request, response) -> None:
        self._apply_link_state(request.link_state)
        response.status_message = "SetLinkState: success"

    def _apply_link_state(self, state: LinkState) -> None:
        self._sim.set_link_state(
            state.link_name,
            xyz(state.pose.position),
            quaternion_of(state.pose),
            xyz(state.twist.linear),
            xyz(state.twist.angular),
            state.reference_frame,
        )

    def _on_set_link_state(self, state: LinkState) -> None:
        try:
            with self._lock:
                self._apply_link_state(state)
        except (WorldError, ValueError, ArithmeticError) as error:  # numbers too large for a step: a warning too
            logwarn_every(5.0, "set_link_state", "/gazebo/set_link_state: %s" % error)

    def _get_link_properties(self, request, response) -> None:
        properties = self._sim.link_properties(request.link_name)
        response.com = pose_msg(properties.pop("com_position"), properties.pop("com_orientation"))
        for field, value in properties.items():
            setattr(response, field, value)
        response.status_message = "GetLinkProperties: got properties"

    def _set_link_properties(self, request, response) -> None:
        self._sim.set_link_properties(
            request.link_name,
            xyz(request.com.position),
            quaternion_of(request.com),
            request.gravity_mode,
            request.mass,
            (request.ixx, request.ixy, request.ixz, request.iyy, request.iyz, request.izz),
        )
        response.status_message = "SetLinkProperties: properties set"

    # --- joints ---------------------------------------------------------------------------------------------
    def _get_joint_properties(self, request, response) -> None:
        for field, value in self._sim.joint_properties(request.joint_name).items():
            setattr(response, field, value)
        response.status_message = "GetJointProperties: got properties"

    def _set_joint_properties(self, request, response) -> None:
        config: ODEJointProperties = request.ode_joint_config
        values = {field: list(getattr(config, field))[0] for field in config.__slots__ if getattr(config, field)}
        self._sim.set_joint_properties(request.joint_name, **values)
        response.status_message = "SetJointProperties: properties set"

    def _set_model_configuration(self, request, response) -> None:
        if len(request.joint_names) != len(request.joint_positions):
            raise WorldError(
                "%d joint names but %d positions" % (len(request.joint_names), len(request.joint_positions))
            )
        self._sim.set_model_configuration(request.model_name, list(request.joint_names), list(request.joint_positions))
        response.status_message = "SetModelConfiguration: success"

    # --- forces ---------------------------------------------------------------------------------------------
    def _apply_body_wrench(self, request, response) -> None:
        self._sim.apply_body_wrench(
            request.body_name,
            request.reference_frame,
            xyz(request.reference_point),
            xyz(request.wrench.force),
            xyz(request.wrench.torque),
            request.start_time.to_sec(),
            request.duration.to_sec(),
        )
        response.status_message = "ApplyBodyWrench: wrench applied"

    def _clear_body_wrenches(self, request, response) -> None:
        self._sim.clear_body_wrenches(request.body_name)

    def _apply_joint_effort(self, request, response) -> None:
        self._sim.apply_joint_effort(
            request.joint_name, request.effort, request.start_time.to_sec(), request.duration.to_sec()
        )
        response.status_message = "ApplyJointEffort: effort set"

    def _clear_joint_forces(self, request, response) -> None:
        self._sim.clear_joint_forces(request.joint_name)

    # --- physics --------------------------------------------------------------------------------------------
    def _get_physics_properties(self, _request, response) -> None:
        properties = self._sim.physics_properties()
        response.time_step = properties["time_step"]
        response.max_update_rate = properties["max_update_rate"]
        response.gravity = Vector3(*properties["gravity"])
        response.ode_config = ODEPhysics(**properties["ode_config"])
        response.pause = self._is_paused()
        response.status_message = "GetPhysicsProperties: got properties"

    def _set_physics_properties(self, request, response) -> None:
        ode = request.ode_config
        # world.control checks that both are finite and in range; here whether /clock would still advance.
        time_step, rate = request.time_step, request.max_update_rate
        if 0 < time_step < math.inf and 0 <= rate < math.inf:
            problem = pacing_problem(request.time_step, request.max_update_rate, self._pub_clock_frequency)
            if problem:
                raise WorldError(problem)
        warnings = self._sim.set_physics_properties(
            time_step=request.time_step,
            max_update_rate=request.max_update_rate,
            gravity=xyz(request.gravity),
            iterations=ode.sor_pgs_iters,
            erp=ode.erp,
            cfm=ode.cfm,
            contact_surface_layer=ode.contact_surface_layer,
            contact_max_correcting_vel=ode.contact_max_correcting_vel,
            max_contacts=ode.max_contacts,
            auto_disable_bodies=ode.auto_disable_bodies,
            sor_pgs_precon_iters=ode.sor_pgs_precon_iters,
            sor_pgs_w=ode.sor_pgs_w,
            sor_pgs_rms_error_tol=ode.sor_pgs_rms_error_tol,
        )
        response.status_message = "SetPhysicsProperties: physics set" + (
            " (warnings: %s)" % "; ".join(warnings) if warnings else ""
        )
        self._on_time_change("physics")

    def _reset_world(self) -> None:
        self._sim.reset_world()
        self._on_time_change("reset_world")

    def _reset_simulation(self) -> None:
        self._sim.reset_simulation()
        self.next_states_time = 0.0
        self._on_time_change("reset_simulation")

    # --- state topics ---------------------------------------------------------------------------------------
    def publish_states(self, now: float) -> None:
        """Publish model_states and link_states if someone listens and they are due (call from the sim loop)."""
        if now < self.next_states_time:
            return
        self.next_states_time = now + self.states_period
        if self._model_states_pub.get_num_connections():
            states = ModelStates()
            for name in self._sim.models:
                position, quaternion, linear, angular = self._sim.get_model_state(name, "")
                states.name.append(name)
                states.pose.append(pose_msg(position, quaternion))
                states.twist.append(twist_msg(linear, angular))
            self._model_states_pub.publish(states)
        if self._link_states_pub.get_num_connections():
            states = LinkStates()
            for name, model in self._sim.models.items():
                for link in model.links:
                    scoped = "%s::%s" % (name, link)
                    position, quaternion, linear, angular = self._sim.get_link_state(scoped, "")
                    states.name.append(scoped)
                    states.pose.append(pose_msg(position, quaternion))
                    states.twist.append(twist_msg(linear, angular))
            self._link_states_pub.publish(states)


def request_strings(request) -> List[str]:
    """The string fields of a service request, one level of messages deep (model_state.model_name and the like)."""
    found = []
    for field in getattr(request, "__slots__", ()):
        value = getattr(request, field, None)
        if isinstance(value, str):
            found.append(value)
        else:
            found += [getattr(value, f) for f in getattr(value, "__slots__", ()) if isinstance(getattr(value, f), str)]
    return found


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
