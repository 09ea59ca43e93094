"""gazebo_ros_control's ROS side (world.plugins.ros_control): the hardware simulation and controller manager of
control.plugin, stepped before every physics step (Simulation.step_hooks), and the controller manager's services
under ``<robot namespace>/controller_manager/``, with controller_manager_msgs' types.

Locks: the world lock is held while the simulation steps; this manager's own lock guards its controllers, taken by
the step and by the services and topic callbacks, never while waiting for the world lock or actionlib's."""
from __future__ import annotations

import threading
from typing import Any, Dict, List, Tuple

import rosgraph
import rospy
from controller_manager_msgs.msg import ControllerState, HardwareInterfaceResources
from controller_manager_msgs.srv import (
    ListControllers,
    ListControllersResponse,
    ListControllerTypes,
    ListControllerTypesResponse,
    LoadController,
    LoadControllerResponse,
    ReloadControllerLibraries,
    ReloadControllerLibrariesResponse,
    SwitchController,
    SwitchControllerResponse,
    UnloadController,
    UnloadControllerResponse,
)
from std_msgs.msg import Bool

from turtle_sim_ode.control.ode_joint import ode_sim_joints
from turtle_sim_ode.control.plugin import RosControl, RosControlConfig, unstable_velocity_pids
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, subscriber
from turtle_sim_ode.ros.plugins.ros_control_topics import ControllerTopics
from turtle_sim_ode.world.plugins.ros_control import RosControlPluginConfig

LOG = {"debug": rospy.logdebug, "info": rospy.loginfo, "warn": rospy.logwarn, "error": rospy.logerr}
SERVICES = (
    ("list_controllers", ListControllers),
    ("list_controller_types", ListControllerTypes),
    ("load_controller", LoadController),
    ("unload_controller", UnloadController),
    ("switch_controller", SwitchController),
    ("reload_controller_libraries", ReloadControllerLibraries),
)


def uncached_param(key: str, default: Any) -> Any:
    """The parameter server's value at ``key``, asked of the master: rospy.get_param answers from its cache once the
    node caches any parameter (rosout caches one), and for "/" that cache is a part of the tree."""
    try:
        return rosgraph.Master(rospy.get_name()).getParam(rospy.resolve_name(key))
    except rosgraph.MasterError:  # not set
        return default


def _log(level: str, text: str) -> None:
    LOG[level]("gazebo_ros_control: " + text)


class RosControlInterface(Periodic):
    """One robot's controller manager on ROS. Publishing happens after each control update, not on a schedule."""

    def __init__(self, context: ModelContext, config: RosControlPluginConfig) -> None:
        super().__init__(float("inf"))
        model = context.model
        # gazebo_ros's spawn gives a plugin its robot_namespace only where the plugin names none
        params = dict(config.params)
        if "robotNamespace" not in params and context.namespace:
            params["robotNamespace"] = context.namespace
        settings = RosControlConfig.read(params, context.name, context.sim.physics.time_step)
        self.namespace = "/" + settings.robot_namespace.strip("/")
        robot_params = uncached_param(self.namespace, {})
        sim_joints = ode_sim_joints(model)
        self.control = RosControl(
            settings, model.robot, sim_joints, robot_params if isinstance(robot_params, dict) else {}, _log
        )
        inertias = {name: joint.handle.moved_inertia() for name, joint in sim_joints.items()}
        for warning in unstable_velocity_pids(self.control.hw, inertias, context.sim.physics.time_step):
            _log("warn", warning)
        self.lock = threading.Lock()
        self.topics: Dict[str, ControllerTopics] = {}
        base = self.namespace.rstrip("/") + "/controller_manager/"
        self.services = [rospy.Service(base + name, kind, getattr(self, "_" + name)) for name, kind in SERVICES]
        self.e_stop = None
        if settings.e_stop_topic:
            self.e_stop = subscriber(settings.e_stop_topic, Bool, self._on_e_stop, 1)
        self.sim = context.sim
        self.name = context.name
        context.sim.step_hooks[context.name] = self
        rospy.loginfo(f"gazebo_ros_control: Starting gazebo_ros_control plugin in namespace: {self.namespace}")

    # --- the step hook (world lock held) --------------------------------------------------
    def step(self, now: float, dt: float) -> None:
        with self.lock:
            self.control.step(now, dt)
            taken = [(topics, topics.take()) for topics in self.topics.values()]
        for topics, pending in taken:
            topics.send(pending)

    def reset(self) -> None:
        with self.lock:
            self.control.reset()

    def _on_e_stop(self, msg: Bool) -> None:
        with self.lock:
            self.control.e_stop = msg.data

    # --- services ----------------------------------------------------------------------------
    def _list_controllers(self, _request: Any) -> ListControllersResponse:
        with self.lock:
            listing = self.control.manager.listing()
        return ListControllersResponse(
            controller=[
                ControllerState(
                    name=name,
                    state=state,
                    type=kind,
                    claimed_resources=[HardwareInterfaceResources(i, list(r)) for i, r in claims],
                )
                for name, state, kind, claims in listing
            ]
        )

    def _list_controller_types(self, _request: Any) -> ListControllerTypesResponse:
        types = self.control.manager.types()
        return ListControllerTypesResponse(types=[t for t, _ in types], base_classes=[b for _, b in types])

    def _load_controller(self, request: Any) -> LoadControllerResponse:
        name = request.name.strip("/")
        where = f"{self.namespace.rstrip('/')}/{name}"
        params = uncached_param(where, {}) if name else {}
        with self.lock:
            if not name or not self.control.manager.load(name, params if isinstance(params, dict) else {}, where):
                return LoadControllerResponse(ok=False)
            controller = self.control.manager.find(name).controller
            try:
                self.topics[name] = ControllerTopics(self.namespace, name, controller, self.lock)
            except Exception as error:  # a topic of another type already there, ...: the load is undone
                self.control.manager.unload(name)
                _log("error", f"Initializing controller '{name}' failed: {error}")
                return LoadControllerResponse(ok=False)
        return LoadControllerResponse(ok=True)

    def _unload_controller(self, request: Any) -> UnloadControllerResponse:
        with self.lock:
            ok = self.control.manager.unload(request.name)
            topics = self.topics.pop(request.name, None) if ok else None
        if topics is not None:
            topics.close()
        return UnloadControllerResponse(ok=ok)

    def _switch_controller(self, request: Any) -> SwitchControllerResponse:
        with self.lock:
            ok = self.control.manager.switch(request.start_controllers, request.stop_controllers, request.strictness)
        return SwitchControllerResponse(ok=ok)

    def _reload_controller_libraries(self, request: Any) -> ReloadControllerLibrariesResponse:
        with self.lock:
            ok = self.control.manager.reload_libraries(request.force_kill)
            closed: List[Tuple[str, ControllerTopics]] = list(self.topics.items()) if ok else []
            if ok:
                self.topics.clear()
        for _, topics in closed:
            topics.close()
        return ReloadControllerLibrariesResponse(ok=ok)

    # --- Periodic ------------------------------------------------------------------------------
    def publish(self, stamp: rospy.Time, now: float) -> None:
        pass

    def close(self) -> None:
        if self.sim.step_hooks.get(self.name) is self:
            del self.sim.step_hooks[self.name]
        for service in self.services:
            service.shutdown()
        if self.e_stop is not None:
            self.e_stop.unregister()
        with self.lock:
            topics, self.topics = list(self.topics.values()), {}
        for entry in topics:
            entry.close()


def interfaces(context: ModelContext, config: RosControlPluginConfig) -> List[Periodic]:
    """The plugin's ROS side; a configuration it cannot run with is logged (as upstream's fatal message) and the
    model goes on without it."""
    try:
        return [RosControlInterface(context, config)]
    except ValueError as error:
        rospy.logfatal(f"gazebo_ros_control: {error}: plugin not active")
        return []
