"""Gazebo classic's ROS API (gazebo_ros, Noetic) on a Simulation: the /gazebo/* services and topics with
gazebo_msgs types, so code written for Gazebo runs unchanged.

Logical failures answer success: false with a status_message, as gazebo_ros does; the service call itself
succeeds. Unlike gazebo_ros, spawning never waits on sim time (Gazebo's spawn hangs while paused or at /clock 0).
"""
from __future__ import annotations

import contextlib
import math
import threading
from typing import Callable, List, Tuple

from gazebo_msgs import srv as gz
from gazebo_msgs.msg import LinkState, LinkStates, ModelState, ModelStates, ODEJointProperties, ODEPhysics
from geometry_msgs.msg import Vector3
import rospy
from std_msgs.msg import ColorRGBA
from std_srvs.srv import Empty, EmptyResponse

from turtle_sim_ode.ros.msg_values import Vec3, pose_msg, quaternion_of, rgba, twist_msg, xyz
from turtle_sim_ode.ros.names import shorten_names_in
from turtle_sim_ode.ros.pacing import pacing_problem
from turtle_sim_ode.ros.physics_reconfigure import PhysicsReconfigure
from turtle_sim_ode.ros.spawn import ModelSpawner
from turtle_sim_ode.ros.throttle import logwarn_every
from turtle_sim_ode.ros.wire import heard
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.values import WorldError

State = Tuple[Vec3, Tuple[float, float, float, float], Vec3, Vec3]


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
        self._on_delete = on_delete
        self._spawn = ModelSpawner(sim, lock, on_spawn, on_delete)
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
    def states_due(self) -> float:
        """Sim time of the next model_states or link_states message; infinite while nobody listens, so that the
        unpaced loop need not stop for them (a subscriber that comes gets the next step's)."""
        if heard(self._model_states_pub) or heard(self._link_states_pub):
            return self.next_states_time
        return math.inf

    def publish_states(self, now: float) -> None:
        """Publish model_states and link_states if someone listens and they are due (call from the sim loop)."""
        if now < self.next_states_time:
            return
        self.next_states_time = now + self.states_period
        if heard(self._model_states_pub):
            states = ModelStates()
            for name in self._sim.models:
                position, quaternion, linear, angular = self._sim.get_model_state(name, "")
                states.name.append(name)
                states.pose.append(pose_msg(position, quaternion))
                states.twist.append(twist_msg(linear, angular))
            self._model_states_pub.publish(states)
        if heard(self._link_states_pub):
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
