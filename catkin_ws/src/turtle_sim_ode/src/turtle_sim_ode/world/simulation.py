"""ROS-free simulation: a PhysicsWorld with named models, the drive plugins found in them, and
Gazebo's world API over them (see world.control)."""
from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import Dict, List, Mapping, Optional, Protocol, Sequence, Tuple, Union

from turtle_sim_ode.models.builder import build_model
from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import Transform, Vec3, compose, inverse, quat_from_rpy
from turtle_sim_ode.models.includes import resolve_includes, sun_lights
from turtle_sim_ode.models.lights import Light
from turtle_sim_ode.models.meshes import load_meshes, uses_meshes
from turtle_sim_ode.models.resources import ResourcePaths
from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.sdf_world import World
from turtle_sim_ode.models.transforms import rpy_of
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import RobotModel
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.physics.settings import PhysicsParams
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.sensors.config import model_sensors
from turtle_sim_ode.sensors.scene import Scene
from turtle_sim_ode.world.control import WorldControl
from turtle_sim_ode.world.entities import SCOPE, WORLD_FRAMES
from turtle_sim_ode.world.lights import LightControl
from turtle_sim_ode.world.plugins import DriveRobot, ModelPlugins, read_plugins
from turtle_sim_ode.world.records import Load, QuatXYZW
from turtle_sim_ode.world.rubble import RUBBLE, rubble
from turtle_sim_ode.world.world_state import apply_world_state
from turtle_sim_ode.world.values import WorldError, update_rate, vector

Pose6 = Tuple[float, float, float, float, float, float]
# (x, y, z, roll, pitch, yaw), or (position, quaternion (x, y, z, w)) as in geometry_msgs/Pose.
SpawnPose = Union[Sequence[float], Tuple[Vec3, QuatXYZW]]

log = logging.getLogger(__name__)


class StepHook(Protocol):
    """Work a plugin does before every physics step (``step(sim_time, time_step)``) and forgets on a reset."""

    def step(self, now: float, dt: float) -> None:
        ...

    def reset(self) -> None:
        ...


@dataclass(frozen=True)
class _Spawned:
    """What reset_world restores: the model frame's pose (static models), the world pose of one
    link of each body, and the joint positions, as spawned."""

    pose: Transform
    link_poses: Dict[str, Transform]
    joint_positions: Dict[str, float]

    @classmethod
    def of(cls, model: BuiltModel) -> "_Spawned":
        link_poses: Dict[str, Transform] = {}
        bodies = set()
        for link, frame in model.links.items():
            if frame.body is not None and id(frame.body) not in bodies:
                bodies.add(id(frame.body))
                link_poses[link] = model.link_transform(link)
        return cls(model.model_transform(), link_poses, {name: handle.angle() for name, handle in model.joints.items()})


class Simulation(WorldControl, LightControl):
    """Models by name in one physics world, stepped with their drives and scheduled loads."""

    def __init__(
        self,
        physics_params: Optional[PhysicsParams] = None,
        drive_overrides: Optional[Mapping[str, object]] = None,
        max_update_rate: Optional[float] = None,
        contact_kernel: bool = True,
    ) -> None:
        """``max_update_rate``: steps per wall second the node should pace to (Gazebo's
        real_time_update_rate; 0 = as fast as possible); default: real time. ``contact_kernel``: as
        PhysicsWorld's."""
        self.physics = PhysicsWorld(physics_params, contact_kernel)
        self.models: Dict[str, BuiltModel] = {}
        self.robots: Dict[str, DriveRobot] = {}
        self.plugins: Dict[str, ModelPlugins] = {}  # what each model's plugin tags ask of the ROS side
        self.max_update_rate = (
            1.0 / self.physics.time_step if max_update_rate is None else update_rate(max_update_rate, "max_update_rate")
        )
        self.loads: List[Load] = []
        # What runs before each physics step beside the drives, keyed by model name (gazebo_ros_control's update) or
        # by "model::what" where a model has more (a vacuum gripper's); deleting a model drops both kinds.
        self.step_hooks: Dict[str, StepHook] = {}
        self._drive_overrides = dict(drive_overrides or {})
        self._spawned: Dict[str, _Spawned] = {}
        # The loaded world's lights by name (see world.lights) and sky colour for the cameras (None: Gazebo's).
        self.lights: Dict[str, Light] = {}
        self.sky_colour: Optional[Tuple[float, float, float]] = None
        # The loaded world's <spherical_coordinates> (latitude_deg, longitude_deg, elevation, heading_deg); GPS plugins.
        self.spherical_coordinates: Optional[Tuple[float, float, float, float]] = None
        self.world_name = "default"  # the loaded world's (Gazebo's scoped sensor names begin with it)
        # What the cameras see of the models (their visuals), whose meshes are read through ``resources``.
        self.scene = Scene(self.models)

    @property
    def resources(self) -> Optional[ResourcePaths]:
        """Where model://, package:// and file:// names are read from (None: no file is read; a mesh is refused):
        collision meshes when a model is spawned, visual meshes when a camera first draws it."""
        return self.scene.resources

    @resources.setter
    def resources(self, paths: Optional[ResourcePaths]) -> None:
        self.scene.resources = paths

    @property
    def sim_time(self) -> float:
        return self.physics.sim_time

    @property
    def real_time_factor(self) -> float:
        """Sim seconds per wall second that ``max_update_rate`` asks for (0: unpaced)."""
        return self.max_update_rate * self.physics.time_step

    # --- models ---------------------------------------------------------------------------
    def spawn_model(
        self,
        name: str,
        robot: RobotModel,
        pose: SpawnPose = (0, 0, 0, 0, 0, 0),
        reference_frame: str = "",
        base: Optional[str] = None,
    ) -> List[str]:
        """Build ``robot`` as model ``name``, with its plugins and sensors, with its model frame at ``pose`` relative to
        ``reference_frame`` (see world.control); return warnings. Its mesh files are read through ``resources``
        (relative names against ``base``, the folder of the file it came from).

        Raises ModelError for a bad name or model, WorldError for a bad pose or frame; the
        world is left as it was.
        """
        if not name:
            raise ModelError("model name is empty")
        if SCOPE in name:
            raise ModelError(f"model name '{name}' must not contain '{SCOPE}'")
        if name in self.models:
            raise ModelError(f"a model named '{name}' already exists")
        robot.base = base
        if uses_meshes(robot):
            load_meshes(robot, self.resources, base)
        sensors = model_sensors(robot)
        model = build_model(self.physics, robot, self._spawn_pose(pose, reference_frame))
        model.name = name
        warnings = list(robot.warnings) + model.warnings
        try:
            plugins = read_plugins(name, robot.plugins, self._drive_overrides, list(model.joints), sensors)
            if len(plugins.drives) > 1:
                warnings.append(
                    f"model has {len(plugins.drives)} drive plugins: only the first "
                    f"({plugins.drives[0].filename}) is used"
                )
            if plugins.drives:
                self.robots[name] = plugins.drives[0].make_robot(model)
                self.robots[name].reset_odometry(self.sim_time)
        except (ModelError, ValueError) as error:
            model.remove()
            raise ModelError(f"model '{name}': {error}") from None
        self.models[name] = model
        self.plugins[name] = plugins
        self._spawned[name] = _Spawned.of(model)
        return warnings + plugins.warnings + sensors.warnings

    def models_seen_by_cameras(self, robot: RobotModel) -> List[RobotModel]:
        """The models whose visual meshes a spawn of ``robot`` should read ahead: ``robot`` if a camera exists or it
        has one, and every model if it brings the first camera; ModelError if its sensor blocks are bad."""
        cameras_before = any(plugins.cameras for plugins in self.plugins.values())
        brings_camera = bool(model_sensors(robot).cameras)
        seen = [robot] if cameras_before or brings_camera else []
        if brings_camera and not cameras_before:
            seen += [model.robot for model in self.models.values()]
        return seen

    def _spawn_pose(self, pose: SpawnPose, reference_frame: str) -> Pose6:
        """(x, y, z, roll, pitch, yaw) in the world for build_model."""
        size = len(pose) if isinstance(pose, (tuple, list)) else 0
        if size == 6:
            x, y, z, roll, pitch, yaw = vector(pose, 6, "pose")
            if reference_frame in WORLD_FRAMES:
                return (x, y, z, roll, pitch, yaw)
            qw, qx, qy, qz = quat_from_rpy(roll, pitch, yaw)
            given: Tuple[Sequence[float], Sequence[float]] = ((x, y, z), (qx, qy, qz, qw))
        elif size == 2:
            given = (pose[0], pose[1])  # type: ignore[assignment]
        else:
            raise WorldError(f"pose must be (x, y, z, roll, pitch, yaw) or (position, quaternion), " f"got {pose!r}")
        (x, y, z), (qx, qy, qz, qw) = self.to_world(reference_frame, *given)
        roll, pitch, yaw = rpy_of((qw, qx, qy, qz))
        return (x, y, z, roll, pitch, yaw)

    def spawn_urdf(
        self, name: str, urdf: str, pose: SpawnPose = (0, 0, 0, 0, 0, 0), reference_frame: str = ""
    ) -> List[str]:
        """Parse a URDF and ``spawn_model`` it (ModelError if it is bad)."""
        return self.spawn_model(name, parse_urdf(urdf), pose, reference_frame)

    def spawn_sdf(
        self, name: str, sdf: str, pose: SpawnPose = (0, 0, 0, 0, 0, 0), reference_frame: str = ""
    ) -> List[str]:
        """Parse an SDF <model> and ``spawn_model`` it; its own <pose> is not applied."""
        return self.spawn_model(name, parse_sdf_model(sdf), pose, reference_frame)

    def load_world(self, world: World) -> List[str]:
        """Take the world's physics and pacing, spawn its models in the world's order; return warnings (one per
        <include> that cannot be resolved). The world has a ground only where a ground plane model brings one.

        WorldError if models exist already, ModelError for bad physics or models; the world
        is left as it was.
        """
        if self.models:
            raise WorldError(f"load_world needs an empty world, but models {list(self.models)} exist")
        params = world.physics.apply(self.physics.params)
        sdf = world.physics
        rate = self.max_update_rate
        if sdf.real_time_update_rate is not None:
            rate = update_rate(sdf.real_time_update_rate, "world <real_time_update_rate>")
        elif sdf.real_time_factor is not None:
            rate = update_rate(sdf.real_time_factor, "world <real_time_factor>") / params.time_step
        lights = world.lights if self.resources is None else sun_lights(world, self.resources)
        old_params, old_rate = self.physics.params, self.max_update_rate
        self.physics.set_params(params)
        self.lights, self.sky_colour = {light.name: light for light in lights}, world.background
        self.had_sun = self.light_direction is not None
        self.spherical_coordinates = world.spherical_coordinates
        self.world_name = world.name
        self.max_update_rate = rate
        warnings = list(world.warnings)
        includes = world.includes
        try:
            models = list(world.models)
            if includes:
                included, includes = resolve_includes(world, self.resources)
                models = sorted(models + included, key=lambda entry: entry.index)
            self.physics.remove_ground()
            for entry in models:
                warnings.extend(
                    f"model '{entry.name}': {warning}"
                    for warning in self.spawn_model(entry.name, entry.model, entry.spawn_pose, base=entry.base)
                )
            for plugin in (plugin for plugin in world.plugins if plugin.filename == RUBBLE):
                for name, piece, pose in rubble(plugin):
                    warnings.extend(f"model '{name}': {warning}" for warning in self.spawn_model(name, piece, pose))
        except Exception:
            for name in list(self.models):
                self.delete(name)
            self.physics.place_ground((0.0, 0.0, 1.0), 0.0)
            self.physics.set_params(old_params)
            self.max_update_rate = old_rate
            self.lights, self.sky_colour, self.had_sun = {}, None, False
            self.spherical_coordinates, self.world_name = None, "default"
            raise
        if world.state is not None:
            warnings.extend(apply_world_state(world.state, self.physics, self.models, self.lights))
            for robot in self.robots.values():  # odometry starts from the saved time and pose
                robot.reset_odometry(self.sim_time)
        for include in includes:
            named = f" (model '{include.name}')" if include.name else ""
            warnings.append(f"cannot resolve {include.uri}{named}: not spawned")
        warnings.extend(
            f"world plugin {plugin.filename} ({plugin.name}) is not supported: ignored"
            for plugin in world.plugins
            if plugin.filename != RUBBLE
        )
        return warnings

    def delete(self, name: str) -> None:
        """Remove model ``name`` and the loads on it; WorldError if there is none."""
        model = self._model(name)
        del self.models[name]
        del self._spawned[name]
        self.robots.pop(name, None)
        for key in [key for key in self.step_hooks if key == name or key.startswith(name + SCOPE)]:
            del self.step_hooks[key]
        self.plugins.pop(name, None)
        self.loads = [load for load in self.loads if load.model != name]
        model.remove()

    # --- time ------------------------------------------------------------------------------
    def step(self) -> None:
        """One physics step with every drive's motors and every due load set for it."""
        now = self.physics.sim_time
        dt = self.physics.time_step
        for robot in self.robots.values():
            robot.drive.update(now, dt)
        for hook in self.step_hooks.values():
            hook.step(now, dt)
        if self.loads:
            self.apply_loads()
        self.physics.step()

    def reset_world(self) -> None:
        """Gazebo's reset_world: every model back at its spawn pose and joint positions, at
        rest; loads cleared; drives stopped and their odometry reset. Sim time goes on."""
        self.loads = []
        for name, model in self.models.items():
            spawned = self._spawned[name]
            if model.robot.static:
                model.set_transform(spawned.pose)
            for link, pose in spawned.link_poses.items():
                frame = model.links[link]
                body = frame.body
                assert body is not None  # only links with a body are recorded
                position, quaternion = compose(pose, inverse(frame.offset))
                body.setPosition(position)
                body.setQuaternion(quaternion)
                body.setLinearVel((0.0, 0.0, 0.0))
                body.setAngularVel((0.0, 0.0, 0.0))
            for joint, angle in spawned.joint_positions.items():
                model.joints[joint].resync(angle)
        now = self.sim_time
        for robot in self.robots.values():
            robot.drive.stop()
            robot.reset_odometry(now)
        for hook in self.step_hooks.values():
            hook.reset()

    def reset_simulation(self) -> None:
        """Gazebo's reset_simulation: ``reset_world`` with sim time back at 0."""
        self.physics.reset_time()
        self.reset_world()
