"""Parse an SDF 1.4-1.7 <world> (no file access): physics, inline models, includes for the caller to resolve, plugins,
lights, a saved state."""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, List, Optional, Set, Tuple
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.lights import SUN, Light, parse_light
from turtle_sim_ode.models.materials import RGB, rgb_of
from turtle_sim_ode.models.nested import read_pose
from turtle_sim_ode.models.sdf import parse_model
from turtle_sim_ode.models.sdf_parts import optional_float, read_bool, read_float, read_plugin, read_version
from turtle_sim_ode.models.text import ModelError, child_text, parse_xml
from turtle_sim_ode.models.description import GazeboPlugin, Pose, RobotModel, Vec3
from turtle_sim_ode.models.urdf import _vec3
from turtle_sim_ode.models.world_state import WorldState, parse_world_state

if TYPE_CHECKING:
    from turtle_sim_ode.physics.settings import PhysicsParams

# <world> children that change nothing the simulator models.
SILENT_WORLD_TAGS = ("light", "scene", "gui", "atmosphere", "spherical_coordinates", "magnetic_field", "wind", "audio")
# <gravity> when a world has none: SDF's default (sdformat's world.sdf).
SDF_GRAVITY: Vec3 = (0.0, 0.0, -9.8)
GROUND_PLANE_URI = "model://ground_plane"
SUN_URI = "model://sun"
# Gazebo's own inline copy of its ground plane (worlds saved from the GUI contain one).
GROUND_PLANE_NAME = "ground_plane"


@dataclass(frozen=True)
class SdfPhysics:
    """<physics type="ode"> and <gravity>; None where the world leaves the simulator's default."""

    max_step_size: Optional[float] = None
    real_time_factor: Optional[float] = None
    real_time_update_rate: Optional[float] = None
    solver: Optional[str] = None
    iterations: Optional[int] = None
    cfm: Optional[float] = None
    erp: Optional[float] = None
    contact_max_correcting_vel: Optional[float] = None
    contact_surface_layer: Optional[float] = None
    gravity: Optional[Vec3] = None
    sor: Optional[float] = None

    def apply(self, params: PhysicsParams) -> PhysicsParams:
        """A copy of ``params`` with the values this world sets (real-time pacing is the
        caller's); ModelError if they are out of range."""
        given = {
            "time_step": self.max_step_size,
            "solver": self.solver,
            "solver_iterations": self.iterations,
            "cfm": self.cfm,
            "erp": self.erp,
            "contact_max_correcting_vel": self.contact_max_correcting_vel,
            "contact_surface_layer": self.contact_surface_layer,
            "gravity": self.gravity,
            "sor": self.sor,
        }
        result = replace(params, **{k: v for k, v in given.items() if v is not None})
        try:
            result.validate()
        except ValueError as error:
            raise ModelError(f"world <physics>: {error}") from None
        return result


@dataclass(frozen=True)
class WorldModel:
    """A <model> written inline in the world, at ``pose`` (its model frame)."""

    name: str
    pose: Pose
    model: RobotModel
    # The folder of the file the model came from (an <include>d model's), for its relative mesh names.
    base: Optional[str] = None
    # Its place among the world's <model>s and <include>s: Gazebo loads them in that order.
    index: int = field(default=0, compare=False)

    @property
    def spawn_pose(self) -> Tuple[float, float, float, float, float, float]:
        """(x, y, z, roll, pitch, yaw) for build_model."""
        return self.pose.xyz + self.pose.rpy


@dataclass(frozen=True)
class Include:
    """An <include> for the caller to resolve (model:// files are never opened here)."""

    uri: str
    name: Optional[str] = None
    pose: Pose = Pose()
    static: Optional[bool] = None
    index: int = field(default=0, compare=False)  # as WorldModel's


@dataclass
class World:
    """<world>: physics, inline models, includes for the caller, world plugins."""

    name: str
    physics: SdfPhysics
    models: List[WorldModel] = field(default_factory=list)
    includes: List[Include] = field(default_factory=list)
    plugins: List[GazeboPlugin] = field(default_factory=list)
    # model://ground_plane (or an inline "ground_plane" model); without one the world has no ground, as in Gazebo.
    ground_plane: bool = False
    sun: bool = False
    # The world's <light>s in order (model://sun is models.lights.SUN); <scene><background> (None: Gazebo's).
    lights: List[Light] = field(default_factory=list)
    state: Optional[WorldState] = None  # the first <state> (see models.world_state)
    background: Optional[RGB] = None
    # <spherical_coordinates>: latitude_deg, longitude_deg, elevation, heading_deg (None: Gazebo's zeros).
    spherical_coordinates: Optional[Tuple[float, float, float, float]] = None
    # <gui><camera><pose>: where Gazebo's client first looks from (None: its default view).
    user_camera: Optional[Pose] = None
    warnings: List[str] = field(default_factory=list)


def _parse_physics(world: Element, warnings: List[str]) -> SdfPhysics:
    blocks = world.findall("physics")
    chosen = next(
        (b for b in blocks if b.get("default", "").lower() in ("true", "1")),
        blocks[0] if blocks else Element("physics"),
    )
    what = "<physics>"
    if chosen.get("type", "ode") != "ode":
        warnings.append(f"<physics type='{chosen.get('type')}'>: only its ODE settings are read")
    # SDF 1.4 keeps gravity in <physics>, later versions in <world>.
    gravity_text = child_text(world, "gravity") or child_text(chosen, "gravity")
    solver = child_text(chosen, "ode/solver/type")
    if solver not in (None, "quick", "world"):
        raise ModelError(f"{what} <ode><solver><type>: expected quick or world, got {solver!r}")
    iterations = optional_float(chosen, "ode/solver/iters", what)
    if iterations is not None and (iterations != int(iterations) or iterations < 1):
        raise ModelError(f"{what} <ode><solver><iters>: expected a positive integer, " f"got {iterations}")
    step = optional_float(chosen, "max_step_size", what)
    if step is not None and step <= 0:
        raise ModelError(f"{what} <max_step_size> must be > 0, got {step}")
    for path, idle in (("ode/solver/precon_iters", "0"), ("ode/solver/use_dynamic_moi_rescaling", "0")):
        if child_text(chosen, path) not in (None, idle, "false"):
            warnings.append(f"{what} <{path}> {child_text(chosen, path)} is not simulated, ignored")
    return SdfPhysics(
        max_step_size=step,
        real_time_factor=optional_float(chosen, "real_time_factor", what),
        real_time_update_rate=optional_float(chosen, "real_time_update_rate", what),
        solver=solver,
        iterations=None if iterations is None else int(iterations),
        cfm=optional_float(chosen, "ode/constraints/cfm", what),
        erp=optional_float(chosen, "ode/constraints/erp", what),
        contact_max_correcting_vel=optional_float(chosen, "ode/constraints/contact_max_correcting_vel", what),
        contact_surface_layer=optional_float(chosen, "ode/constraints/contact_surface_layer", what),
        sor=optional_float(chosen, "ode/solver/sor", what),
        # SDF's default, as Gazebo gives a world without <gravity> (not the simulator's own -9.81).
        gravity=SDF_GRAVITY if gravity_text is None else _vec3(gravity_text, "<gravity>", (0.0, 0.0, 0.0)),
    )


def parse_sdf_world(text: str) -> World:
    """Parse ``<sdf version><world>``: physics, inline models, includes (not opened), plugins."""
    root = parse_xml(text, "SDF")
    if root.tag != "sdf":
        raise ModelError(f"SDF root element must be <sdf>, got <{root.tag}>")
    version = read_version(root)
    worlds = root.findall("world")
    if len(worlds) != 1:
        raise ModelError(f"expected one <world> in <sdf>, found {len(worlds)}")
    element = worlds[0]
    warnings: List[str] = []
    world = World(element.get("name", "default"), _parse_physics(element, warnings), warnings=warnings)
    names: Set[str] = set()
    for index, child in enumerate(element):
        if child.tag == "model":
            model, pose = parse_model(child, version)
            world.ground_plane = world.ground_plane or model.name == GROUND_PLANE_NAME
            if model.name in names:
                raise ModelError(f"two models are named '{model.name}'")
            names.add(model.name)
            world.models.append(WorldModel(model.name, pose, model, index=index))
        elif child.tag == "include":
            uri = child_text(child, "uri")
            if uri is None:
                raise ModelError("<include> needs a <uri>")
            if uri == SUN_URI:
                world.sun = True
                world.lights.append(replace(SUN, name=child_text(child, "name") or SUN.name))
            else:
                world.ground_plane = world.ground_plane or uri.rstrip("/") == GROUND_PLANE_URI
                name = child_text(child, "name")
                if name is not None:
                    if name in names:
                        raise ModelError(f"two models are named '{name}'")
                    names.add(name)
                static = child_text(child, "static")
                world.includes.append(
                    Include(
                        uri,
                        name,
                        read_pose(child, f"<include> '{uri}'"),
                        None if static is None else read_bool(child, "static", f"<include> '{uri}'", False),
                        index,
                    )
                )
        elif child.tag == "plugin":
            world.plugins.append(read_plugin(child, "<world>"))
        elif child.tag == "light":
            world.lights.append(parse_light(child))
        elif child.tag == "state":
            if world.state is None:
                world.state = parse_world_state(element)
        elif child.tag == "gui" and child.find("camera/pose") is not None:
            world.user_camera = read_pose(child.find("camera"), "<gui><camera>")
        elif child.tag == "scene":
            world.background = rgb_of(child_text(child, "background")) or world.background
        elif child.tag == "spherical_coordinates":
            tags = ("latitude_deg", "longitude_deg", "elevation", "heading_deg")
            values = (read_float(child, tag, "<spherical_coordinates>", 0.0) for tag in tags)
            world.spherical_coordinates = tuple(values)  # type: ignore[assignment]
        elif child.tag not in SILENT_WORLD_TAGS + ("physics", "gravity"):
            warnings.append(f"<world> <{child.tag}> is not supported, ignored")
    return world
