"""A model as the simulator takes it, whatever text it came from (URDF, SDF): links with their inertials, collisions
and visuals, joints, Gazebo surfaces, plugins and sensors, as plain dataclasses."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple, Union
from xml.etree.ElementTree import Element

from turtle_sim_ode.models.materials import RGB
from turtle_sim_ode.models.textures import MaterialScript

Vec3 = Tuple[float, float, float]


@dataclass(frozen=True)
class Pose:
    """URDF <origin>: translation and fixed-axis roll, pitch, yaw."""

    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class Inertial:
    mass: float
    origin: Pose
    ixx: float
    ixy: float
    ixz: float
    iyy: float
    iyz: float
    izz: float

    def matrix(self) -> Tuple[Vec3, Vec3, Vec3]:
        return ((self.ixx, self.ixy, self.ixz), (self.ixy, self.iyy, self.iyz), (self.ixz, self.iyz, self.izz))


@dataclass(frozen=True)
class Box:
    size: Vec3


@dataclass(frozen=True)
class Cylinder:
    """Axis along the collision frame's z, like ODE's cylinder."""

    radius: float
    length: float


@dataclass(frozen=True)
class Sphere:
    radius: float


@dataclass(frozen=True)
class Mesh:
    """A collision mesh: ``uri`` as the model text gives it (package://, model://, file:// or a path), scaled per
    axis. The parsers open no file: models.meshes.load_meshes fills ``vertices`` and ``faces`` (ODE trimesh data,
    scaled) from files under the ROS package path and model path before the model is built."""

    uri: str
    scale: Vec3 = (1.0, 1.0, 1.0)
    vertices: Optional[Tuple[Vec3, ...]] = field(default=None, compare=False, repr=False)
    faces: Optional[Tuple[Tuple[int, int, int], ...]] = field(default=None, compare=False, repr=False)
    # ODE's trimesh data of them (physics.trimesh.TriMeshData), built with them outside the world lock.
    prepared: Optional[object] = field(default=None, compare=False, repr=False)


Geometry = Union[Box, Cylinder, Sphere, Mesh]


@dataclass(frozen=True)
class Collision:
    name: str
    origin: Pose
    geometry: Geometry
    # An SDF <plane> (``geometry`` is its thin box): Gazebo's ODE collides with the whole plane, the box's top face.
    plane: bool = False


@dataclass(frozen=True)
class Visual:
    """What the cameras draw of a link (Gazebo's cameras see visuals, not collisions): ``origin`` in the link frame,
    ``color`` from its own material (None: Gazebo's default grey), ``texture`` a material script's with an image
    (models.textures). A mesh's file is read by the cameras."""

    name: str
    origin: Pose
    geometry: Geometry
    color: Optional[RGB] = None
    texture: Optional[MaterialScript] = None
    alpha: float = 1.0  # opacity (URDF rgba alpha; SDF diffuse alpha and <transparency>)


@dataclass
class Link:
    name: str
    inertial: Optional[Inertial] = None
    collisions: List[Collision] = field(default_factory=list)
    visuals: List[Visual] = field(default_factory=list)

    @property
    def color(self) -> Optional[RGB]:
        """The first visual colour (None: Gazebo's default grey): the cameras draw the link's collisions in it where
        its visuals cannot be drawn."""
        return next((visual.color for visual in self.visuals if visual.color is not None), None)


@dataclass(frozen=True)
class JointLimits:
    lower: float = 0.0
    upper: float = 0.0
    effort: float = 0.0
    velocity: float = 0.0


@dataclass(frozen=True)
class JointDynamics:
    damping: float = 0.0
    friction: float = 0.0


@dataclass(frozen=True)
class Joint:
    name: str
    type: str
    parent: str
    child: str
    origin: Pose = Pose()
    axis: Vec3 = (1.0, 0.0, 0.0)
    limits: Optional[JointLimits] = None
    dynamics: JointDynamics = JointDynamics()
    # SDF <joint><pose>: the joint frame (anchor, and the frame ``axis`` is in) relative to
    # the child link frame. URDF joint frames are the child link frame.
    frame: Pose = Pose()


@dataclass(frozen=True)
class GazeboSurface:
    """<gazebo reference="link"> contact tags; None where the URDF says nothing."""

    mu1: Optional[float] = None
    mu2: Optional[float] = None
    kp: Optional[float] = None
    kd: Optional[float] = None
    max_vel: Optional[float] = None
    min_depth: Optional[float] = None
    fdir1: Optional[Vec3] = None
    slip1: Optional[float] = None
    slip2: Optional[float] = None


@dataclass(frozen=True)
class GazeboPlugin:
    filename: str
    name: str
    params: Dict[str, str]


@dataclass(frozen=True)
class SensorElement:
    """A ``<sensor>`` as the model text has it, handed on for the sensors layer to read: a URDF's from a
    ``<gazebo reference="link">`` block (``link`` None where the block names none), an SDF's from its ``<link>``."""

    link: Optional[str]
    element: Element


@dataclass
class RobotModel:
    name: str
    links: Dict[str, Link]
    joints: Dict[str, Joint]
    root: str
    surfaces: Dict[str, GazeboSurface] = field(default_factory=dict)
    plugins: List[GazeboPlugin] = field(default_factory=list)
    sensors: List[SensorElement] = field(default_factory=list)
    warnings: List[str] = field(default_factory=list)
    # SDF: the root link's pose in the model frame, which build_model places at its pose.
    root_pose: Pose = Pose()
    # SDF <static>: collision geoms fixed in the world, no bodies.
    static: bool = False
    # The folder of the file the model came from: its relative mesh names are read against it.
    base: Optional[str] = None
    # The URDF's <transmission> elements, for gazebo_ros_control (control.transmissions reads them).
    transmissions: List[Element] = field(default_factory=list)

    def plugin(self, filename: str) -> Optional[GazeboPlugin]:
        """The first plugin loaded from ``filename`` (e.g. 'libgazebo_ros_kobuki.so')."""
        return next((p for p in self.plugins if p.filename == filename), None)
