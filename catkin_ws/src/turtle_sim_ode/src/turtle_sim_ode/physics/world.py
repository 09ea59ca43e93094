"""ODE world with a ground plane, Gazebo-style contact surfaces and a fixed step."""
from __future__ import annotations

import ctypes
import math
from dataclasses import dataclass, field, replace
from typing import Callable, Dict, Iterable, List, NamedTuple, Optional, Sequence, Set, Tuple

import ode

from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics import sanity
from turtle_sim_ode.physics.contact_kernel import ContactKernel
from turtle_sim_ode.physics.trimesh import LIBODE as _LIBODE
from turtle_sim_ode.physics.trimesh import collide as _collide
from turtle_sim_ode.physics.trimesh import remove_geom, set_quickstep_w

SOLVERS = ("quick", "world")
# The softest contact stiffness (N/m): softer holds no mass up, and its inverse overflows the contact arithmetic.
MIN_KP = 1.0
# Gravity (m/s² per axis) beyond which resting bodies tunnel through the ground and fall until ODE aborts (1e6 does).
MAX_GRAVITY = 1e3

# Gazebo's ODE contact: axis-dependent friction pyramid scaled by the normal force,
# spring-damper softness from kp/kd.
_CONTACT_MODE = oc.CONTACT_MU2 | oc.CONTACT_SOFT_ERP | oc.CONTACT_SOFT_CFM | oc.CONTACT_APPROX1

# How a geom pair's contacts are made, as set on every ode.Contact of the pair (the kernel's TsoPairSurface):
# (mode, fdir_side, adjust_depth, mu, mu2, soft_erp, soft_cfm, slip1, slip2, min_depth, depth_cap, surface_layer,
#  fdir1 x, y, z). ``fdir_side`` names the geom whose fdir1 (in its own frame) is the first friction direction
# (0 none, 1 the pair's first geom, 2 its second); with ``adjust_depth`` each contact's depth is made
# min(depth - min_depth, depth_cap) + surface_layer, so that ODE (which subtracts the world's surface layer and caps
# the push-out at the world's max correcting velocity) acts with the pair's own min_depth and max_vel.
ContactSurface = Tuple[
    int, int, int, float, float, float, float, float, float, float, float, float, float, float, float
]
# How a geom pair's contacts are made: surface, and whether a line contact is merged.
PairContact = Tuple[ContactSurface, bool]
# Where every component of normal x fdir1 is below this, Gazebo's ODE falls back to its own friction directions
# (gazebo-classic deps/opende/src/joints/contact.cpp, dxJointContact::getInfo2: _dequal(t2, 0)).
PARALLEL_FDIR1_TOLERANCE = 1e-6


# PyODE frees an ode.World's C object when the wrapper dies, and dWorldDestroy frees
# every body and joint in it; bodies or joints whose wrappers die later (routine when
# the garbage collector breaks a reference cycle) are then freed twice and the process
# crashes. Worlds are therefore kept for the life of the process (a few hundred bytes
# each); bodies, joints and geoms are still freed with their wrappers.
_WORLDS_KEPT_ALIVE: List[ode.World] = []


def seed_ode_random(seed: int = 0) -> bool:
    """Reseed ODE's process-wide random generator, which the quick solver uses to reorder its constraints:
    a world seeded afresh steps the same way every time (lockstep reproducibility). PyODE has no binding for
    dRandSetSeed, hence ctypes. False if libode cannot be found (runs then differ in the last bits)."""
    if _LIBODE is None:
        return False
    _LIBODE.dRandSetSeed(ctypes.c_ulong(seed))
    return True


def _finite(value: float) -> bool:
    return isinstance(value, (int, float)) and math.isfinite(value)


@dataclass(frozen=True)
class SurfaceParams:
    """Contact surface of one geom, as Gazebo's ODE surface of a collision: friction (<mu1> <mu2> <fdir1> <slip1>
    <slip2>) and contact (<kp> <kd> <minDepth> <maxVel>). ``min_depth`` and ``max_vel`` None: the geom leaves the
    world's contact_surface_layer and contact_max_correcting_vel in force (Gazebo sets them on the link's body;
    body-less geoms take no part, as in Gazebo where static links have no body)."""

    mu: float = 1.0
    mu2: float = 1.0
    kp: float = 1e12
    kd: float = 1.0
    min_depth: Optional[float] = None
    max_vel: Optional[float] = None
    fdir1: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    slip1: float = 0.0
    slip2: float = 0.0

    def validate(self, name: str = "surface") -> None:
        """Raise ValueError naming the first bad field."""
        for attr in ("mu", "mu2", "kd", "slip1", "slip2", "min_depth", "max_vel"):
            value = getattr(self, attr)
            if value is None and attr in ("min_depth", "max_vel"):
                continue
            if not _finite(value) or value < 0:
                raise ValueError(f"{name}.{attr} must be finite and >= 0, got {value!r}")
        if not _finite(self.kp) or self.kp < MIN_KP:
            raise ValueError(f"{name}.kp must be finite and >= {MIN_KP:g} N/m, got {self.kp!r}")
        if len(self.fdir1) != 3 or not all(_finite(v) for v in self.fdir1):
            raise ValueError(f"{name}.fdir1 must be 3 finite numbers, got {self.fdir1!r}")

    def without_body(self) -> "SurfaceParams":
        """This surface on a body-less geom: no min_depth or max_vel (they belong to a body in Gazebo)."""
        if self.min_depth is None and self.max_vel is None:
            return self
        return replace(self, min_depth=None, max_vel=None)


def combine_surfaces(
    a: SurfaceParams,
    b: SurfaceParams,
    time_step: float,
    surface_layer: float = 0.0,
    max_correcting_vel: float = math.inf,
) -> ContactSurface:
    """Gazebo's rule (ODEPhysics::Collide and its ODE's contact joint): min friction and slip, springs in series,
    dampers in parallel; fdir1 of the geom with the smaller mu1 that has one; min_depth and max_vel the smaller of
    the geoms that set them (max_vel at most the world's), else the world's ``surface_layer`` and
    ``max_correcting_vel``."""
    kp = 1.0 / (1.0 / a.kp + 1.0 / b.kp)
    kd = a.kd + b.kd
    denominator = time_step * kp + kd
    erp, cfm = time_step * kp / denominator, 1.0 / denominator
    slip1, slip2 = min(a.slip1, b.slip1), min(a.slip2, b.slip2)
    mode = _CONTACT_MODE | (oc.CONTACT_SLIP1 if slip1 > 0 else 0) | (oc.CONTACT_SLIP2 if slip2 > 0 else 0)
    zero = (0.0, 0.0, 0.0)
    side, fdir1 = 0, zero
    if a.fdir1 != zero:
        side, fdir1 = 1, a.fdir1
    if b.fdir1 != zero and (a.fdir1 == zero or a.mu > b.mu):
        side, fdir1 = 2, b.fdir1
    depths = [s.min_depth for s in (a, b) if s.min_depth is not None]
    speeds = [s.max_vel for s in (a, b) if s.max_vel is not None]
    min_depth = min(depths) if depths else surface_layer
    max_vel = min(min(speeds), max_correcting_vel) if speeds else max_correcting_vel
    # ODE pushes out at (erp / time_step) * depth, capped at its world-wide max correcting velocity: a pair's lower
    # cap is a cap on the depth it sees.
    depth_cap = max_vel * time_step / erp if max_vel < max_correcting_vel else math.inf
    adjust = int(bool(depths or speeds))
    return (
        mode,
        side,
        adjust,
        min(a.mu, b.mu),
        min(a.mu2, b.mu2),
        erp,
        cfm,
        slip1,
        slip2,
        min_depth,
        depth_cap,
        surface_layer,
        float(fdir1[0]),
        float(fdir1[1]),
        float(fdir1[2]),
    )


def _ground_surface(surface: SurfaceParams) -> SurfaceParams:
    """The ground plane's surface: no body (so no min_depth, max_vel) and no frame to turn an fdir1 by."""
    return replace(surface.without_body(), fdir1=(0.0, 0.0, 0.0))


def configure_world(world: ode.World, params: "PhysicsParams") -> None:
    """Gravity and the solver's world-wide settings of ``params`` on an ODE world."""
    world.setGravity(tuple(params.gravity))
    world.setERP(params.erp)
    world.setCFM(params.cfm)
    world.setQuickStepNumIterations(params.solver_iterations)
    world.setContactMaxCorrectingVel(params.contact_max_correcting_vel)
    world.setContactSurfaceLayer(params.contact_surface_layer)
    set_quickstep_w(world, params.sor)


@dataclass
class PhysicsParams:
    """World-wide solver and contact settings."""

    time_step: float = 0.001
    solver: str = "quick"
    solver_iterations: int = 50
    gravity: Tuple[float, float, float] = (0.0, 0.0, -9.81)
    erp: float = 0.2
    cfm: float = 1e-5
    max_contacts: int = 4
    # Caps how fast penetration is pushed out: higher bounces (a 2 m/s impact rebounds
    # at up to this speed), lower lets soft contacts sink under load (force <= cap / cfm).
    contact_max_correcting_vel: float = 0.1
    contact_surface_layer: float = 0.0001
    # The quick step's successive over-relaxation factor (Gazebo's <sor>, ODE's dWorldSetQuickStepW; ODE's own 1.3).
    sor: float = 1.3
    default_surface: SurfaceParams = field(default_factory=SurfaceParams)
    # Gazebo's ground_plane model surface.
    ground_surface: SurfaceParams = field(default_factory=lambda: SurfaceParams(mu=100.0, mu2=50.0))

    def validate(self) -> None:
        """Raise ValueError naming the bad field and its value."""
        if not _finite(self.time_step) or not 0 < self.time_step <= 0.1:
            raise ValueError(f"time_step must be in (0, 0.1] s, got {self.time_step!r}")
        if self.time_step < sanity.MIN_TIME_STEP:
            raise ValueError(
                f"time_step must be at least {sanity.MIN_TIME_STEP:g} s (shorter steps cannot keep /clock moving at "
                f"any useful rate), got {self.time_step!r}"
            )
        if self.solver not in SOLVERS:
            raise ValueError(f"solver must be one of {SOLVERS}, got {self.solver!r}")
        if (
            not isinstance(self.solver_iterations, int)
            or isinstance(self.solver_iterations, bool)
            or not 1 <= self.solver_iterations <= 1000
        ):
            raise ValueError(f"solver_iterations must be an integer in 1..1000, got {self.solver_iterations!r}")
        if len(self.gravity) != 3 or not all(_finite(g) and abs(g) <= MAX_GRAVITY for g in self.gravity):
            raise ValueError(f"gravity must be 3 finite numbers within ±{MAX_GRAVITY:g} m/s², got {self.gravity!r}")
        if not _finite(self.erp) or not 0 <= self.erp <= 1:
            raise ValueError(f"erp must be in [0, 1], got {self.erp!r}")
        if not _finite(self.cfm) or self.cfm < 0:
            raise ValueError(f"cfm must be finite and >= 0, got {self.cfm!r}")
        if self.cfm > sanity.MAX_CFM:
            raise ValueError(f"cfm must be at most {sanity.MAX_CFM:g}, got {self.cfm!r}")
        if (
            not isinstance(self.max_contacts, int)
            or isinstance(self.max_contacts, bool)
            or not 1 <= self.max_contacts <= 64
        ):
            raise ValueError(f"max_contacts must be an integer in 1..64, got {self.max_contacts!r}")
        for name in ("contact_max_correcting_vel", "contact_surface_layer"):
            value = getattr(self, name)
            if not _finite(value) or value < 0:
                raise ValueError(f"{name} must be finite and >= 0, got {value!r}")
        if not _finite(self.sor) or not 0 < self.sor <= 2:
            raise ValueError(f"sor must be in (0, 2], got {self.sor!r}")
        self.default_surface.validate("default_surface")
        self.ground_surface.validate("ground_surface")


class WatchedContact(NamedTuple):
    """One contact point touching a watched geom: ``normal`` points from ``other`` towards
    ``geom`` (moving ``geom`` along it by ``depth`` separates them)."""

    geom: ode.GeomObject
    other: ode.GeomObject
    position: Tuple[float, float, float]
    normal: Tuple[float, float, float]
    depth: float


class ContactWatch:
    """Contacts touching ``geoms`` during the last step (see ``PhysicsWorld.watch_contacts``).

    ``contacts`` is a new list after every step (the ODE contact points as found, before
    contact joints are made from them); ground contacts are included (``other`` is
    ``PhysicsWorld.ground``).
    """

    def __init__(self, geoms: Iterable[ode.GeomObject]) -> None:
        self.geoms = frozenset(geoms)
        self._contacts: List[WatchedContact] = []
        # Set when the step's contacts are still in the contact kernel: read on demand, since most steps'
        # contacts are never asked for (sensors read at their own rates).
        self._fill: Optional[Callable[[], None]] = None

    @property
    def contacts(self) -> List[WatchedContact]:
        if self._fill is not None:
            self._fill()
        return self._contacts


ContactGeom = Tuple[Tuple[float, float, float], Tuple[float, float, float], float]


def _merge_line_contact(contacts: Sequence[ode.Contact]) -> Tuple[Sequence[ode.Contact], Optional[ContactGeom]]:
    """Replace the two end points of a line contact by its centre of pressure (returned with its point).

    A cylinder lying on a surface touches it along a line, but ODE reports only the
    line's two ends. Their friction scrubs against each other when the cylinder pivots:
    a wheel pair turning in place then turns 6.5 % slower than commanded, because the
    robot settles where one end point sticks. One contact at the centre of pressure of
    the (linear, as for a spring foundation) pressure profile pivots freely.
    """
    first, second = contacts
    (x1, y1, z1), normal, depth1, _, _ = first.getContactGeomParams()
    (x2, y2, z2), (nx2, ny2, nz2), depth2, _, _ = second.getContactGeomParams()
    if normal[0] * nx2 + normal[1] * ny2 + normal[2] * nz2 < 0.999:
        return contacts, None  # not one flat line contact
    total = depth1 + depth2
    # Centroid of a trapezoid of heights depth1, depth2, as a fraction from pos1.
    t = (depth1 + 2.0 * depth2) / (3.0 * total) if total > 0 else 0.5
    # Set without its geoms (PyODE then leaves them null): a contact joint never reads them, and PyODE takes
    # four times as long to set them (every wheel, every step).
    merged = ((x1 + t * (x2 - x1), y1 + t * (y2 - y1), z1 + t * (z2 - z1)), normal, depth1 + t * (depth2 - depth1))
    first.setContactGeomParams(*merged)
    return (first,), merged  # its geoms are null now: PyODE could not read it back


def _friction_direction(
    rotation: Sequence[float], fdir1: Tuple[float, float, float], normal: Sequence[float]
) -> Optional[Tuple[float, float, float]]:
    """``fdir1`` (in a geom's frame; ``rotation`` its world rotation, row-major) turned into the world and handed to
    ODE as it is, neither projected onto the contact plane nor normalised, as gazebo-classic's ODEPhysics::Collide
    does. ODE's contact joint then takes it as the first friction direction and normal x fdir1 as the second: a
    wheel's fdir1 "1 0 0" turns with the wheel, so its friction rows tilt and shrink as it rolls, in Gazebo and here.
    None where normal x fdir1 vanishes: Gazebo's ODE then falls back to dPlaneSpace, as stock ODE does without
    dContactFDir1. contact_kernel.c's friction_direction, op for op."""
    x, y, z = fdir1
    wx = rotation[0] * x + rotation[1] * y + rotation[2] * z
    wy = rotation[3] * x + rotation[4] * y + rotation[5] * z
    wz = rotation[6] * x + rotation[7] * y + rotation[8] * z
    cross = (normal[1] * wz - normal[2] * wy, normal[2] * wx - normal[0] * wz, normal[0] * wy - normal[1] * wx)
    if all(abs(c) <= PARALLEL_FDIR1_TOLERANCE for c in cross):
        return None
    return (wx, wy, wz)


class PhysicsWorld:
    """ODE world, collision spaces, a ground plane (at z=0 until a model places or removes it), a fixed-step clock.

    Each model gets its own sub-space (see ``create_model_space``) so pairs inside a
    model are never tested unless the model asks for self-collision. The ground
    plane lives outside every space: its AABB is infinite, so a broadphase adds
    nothing and each registered dynamic geom is tested against it directly.
    """

    def __init__(self, params: Optional[PhysicsParams] = None, contact_kernel: bool = True) -> None:
        """``contact_kernel``: collide in the compiled kernel when it is built (see contact_kernel.py); False keeps
        the Python path, which steps bitwise alike."""
        self.params = params if params is not None else PhysicsParams()
        self.params.validate()
        p = self.params
        self.world = ode.World()
        _WORLDS_KEPT_ALIVE.append(self.world)
        seed_ode_random()
        configure_world(self.world, self.params)
        self.space = ode.HashSpace()
        self.ground = ode.GeomPlane(None, (0.0, 0.0, 1.0), 0.0)
        # Contact joints live until the next step; dropping a wrapper destroys its joint.
        # (No ode.JointGroup: its destructor double-frees joints that still have wrappers.)
        self._contact_joints: List[ode.ContactJoint] = []
        self._contact_count = 0
        self._kernel = ContactKernel.load() if contact_kernel else None
        self._kernel_stale = True  # its tables must be set again before the next step
        self._body_ids: Dict[ode.Body, int] = {}
        self._stepper = self.world.quickStep if p.solver == "quick" else self.world.step
        # sim_time = _time_base + _steps * time_step: exact, and continuous when time_step changes.
        self._time_base = 0.0
        self._steps = 0
        self._static_space: Optional[ode.SpaceBase] = None
        self._self_colliding: List[ode.SpaceBase] = []
        self._surfaces: Dict[ode.GeomObject, SurfaceParams] = {self.ground: _ground_surface(p.ground_surface)}
        self._has_ground = True
        self._ground_given: Optional[SurfaceParams] = None  # the surface of the model that placed it
        # (geom, body, contact) of every dynamic geom, tested against the ground.
        self._ground_tests: List[Tuple[ode.GeomObject, ode.Body, PairContact]] = []
        self._pair_cache: Dict[Tuple[ode.GeomObject, ode.GeomObject], PairContact] = {}
        self._jointed: Set[Tuple[ode.Body, ode.Body]] = set()
        self._pre_step_hooks: List[Callable[[], None]] = []
        self._post_step_hooks: List[Callable[[], None]] = []
        # Contact listeners: geom -> the watches that asked for it (empty: no cost per step).
        self._watches: List[ContactWatch] = []
        self._watched: Dict[ode.GeomObject, List[ContactWatch]] = {}

    # --- clock -----------------------------------------------------------------
    @property
    def sim_time(self) -> float:
        """Simulated seconds since creation or the last ``reset_time``."""
        return self._time_base + self._steps * self.params.time_step

    @property
    def time_step(self) -> float:
        return self.params.time_step

    @property
    def contact_count(self) -> int:
        """Contact joints created in the last step."""
        return self._contact_count

    @property
    def uses_contact_kernel(self) -> bool:
        return self._kernel is not None

    def reset_time(self) -> None:
        """Time back to 0, and ODE's solver randomness with it, as in a fresh world."""
        self._time_base = 0.0
        self._steps = 0
        seed_ode_random()

    def set_time(self, sim_time: float) -> None:
        """Continue from ``sim_time`` (a world file's saved <state>)."""
        self._time_base, self._steps = float(sim_time), 0

    # --- settings ------------------------------------------------------------------
    def set_params(self, params: PhysicsParams) -> None:
        """Switch to new settings between steps (ValueError if invalid, nothing changed).

        Sim time stays continuous across a time step change; contact softness, which
        depends on the time step, is recomputed for the next step.
        """
        params.validate()
        self._time_base, self._steps = self.sim_time, 0
        self.params = params
        configure_world(self.world, self.params)
        self._stepper = self.world.quickStep if params.solver == "quick" else self.world.step
        self._pair_cache.clear()
        self._set_ground_surface(self._ground_given or params.ground_surface)

    @property
    def has_ground(self) -> bool:
        """Whether the ground plane is there (a world without a ground plane model has none, as in Gazebo)."""
        return self._has_ground

    @property
    def has_own_ground(self) -> bool:  # the simulator's own (no world loaded), not one a ground plane model placed
        return self._has_ground and self._ground_given is None

    def place_ground(
        self, normal: Sequence[float], offset: float, surface: Optional[SurfaceParams] = None
    ) -> ode.GeomPlane:
        """Make the ground the plane normal . p = offset (unit ``normal``) with ``surface`` (None: the params'
        ground_surface); return its geom."""
        self.ground.setParams(normal, offset)
        self._has_ground, self._ground_given = True, surface
        self._set_ground_surface(surface or self.params.ground_surface)
        return self.ground

    def remove_ground(self) -> None:
        """No ground plane: nothing collides with it or sees it until ``place_ground``."""
        self._has_ground, self._ground_given = False, None
        self._kernel_stale = True

    def _set_ground_surface(self, surface: SurfaceParams) -> None:
        self._surfaces[self.ground] = _ground_surface(surface)
        for pair in [pair for pair in self._pair_cache if self.ground in pair]:
            del self._pair_cache[pair]
        self._kernel_stale = True
        self._ground_tests = [
            (geom, body, self._pair_contact(self.ground, geom)) for geom, body, _ in self._ground_tests
        ]

    # --- spaces and geoms ---------------------------------------------------------
    def create_model_space(self, self_collide: bool = False) -> ode.SpaceBase:
        """A sub-space for one model's geoms; pairs inside it collide only if asked."""
        space = ode.SimpleSpace(self.space)
        if self_collide:
            self._self_colliding.append(space)
            self._kernel_stale = True
        return space

    def destroy_model_space(self, space: ode.SpaceBase) -> None:
        """Unregister and remove every geom of ``space``, then the space itself."""
        for geom in [space.getGeom(i) for i in range(space.getNumGeoms())]:
            self.unregister_geom(geom)
            remove_geom(space, geom)
        if space in self._self_colliding:
            self._self_colliding.remove(space)
            self._kernel_stale = True
        self.space.remove(space)

    @property
    def static_space(self) -> ode.SpaceBase:
        """Space for body-less obstacles (created on first use to keep steps cheap)."""
        if self._static_space is None:
            self._static_space = ode.SimpleSpace(self.space)
        return self._static_space

    def register_geom(self, geom: ode.GeomObject, surface: Optional[SurfaceParams] = None) -> None:
        """Give ``geom`` a surface; geoms on a body are also tested against the ground."""
        surface = surface if surface is not None else self.params.default_surface
        surface.validate("surface")
        self.unregister_geom(geom)
        body = geom.getBody()
        self._surfaces[geom] = surface if body is not None else surface.without_body()
        self._kernel_stale = True
        if body is not None:
            self._ground_tests.append((geom, body, self._pair_contact(self.ground, geom)))

    def surface(self, geom: ode.GeomObject) -> SurfaceParams:
        """The surface registered for ``geom`` (the default one if none was)."""
        return self._surfaces.get(geom, self.params.default_surface)

    def unregister_geom(self, geom: ode.GeomObject) -> None:
        if self._surfaces.pop(geom, None) is None:
            return
        self._kernel_stale = True
        self._ground_tests = [t for t in self._ground_tests if t[0] is not geom]
        for pair in [pair for pair in self._pair_cache if geom in pair]:
            del self._pair_cache[pair]

    def exclude_collision(self, body_a: ode.Body, body_b: ode.Body) -> None:
        """Never collide these two bodies (they are connected by a joint)."""
        self._jointed.add((body_a, body_b))
        self._jointed.add((body_b, body_a))
        self._kernel_stale = True

    def forget_body(self, body: ode.Body) -> None:
        """Drop ``body`` from the exclusion table before it is destroyed."""
        self._jointed = {pair for pair in self._jointed if body not in pair}
        self._body_ids.pop(body, None)
        self._kernel_stale = True

    def add_pre_step_hook(self, hook: Callable[[], None]) -> None:
        """Call ``hook()`` right before every step's integration, once every force for it is added (e.g. to record
        the state the step starts from)."""
        self._pre_step_hooks.append(hook)

    def remove_pre_step_hook(self, hook: Callable[[], None]) -> None:
        self._pre_step_hooks.remove(hook)

    def add_post_step_hook(self, hook: Callable[[], None]) -> None:
        """Call ``hook()`` after every step (e.g. to track joint turns)."""
        self._post_step_hooks.append(hook)

    def remove_post_step_hook(self, hook: Callable[[], None]) -> None:
        self._post_step_hooks.remove(hook)

    # --- contact listeners ----------------------------------------------------------
    def watch_contacts(self, geoms: Iterable[ode.GeomObject]) -> ContactWatch:
        """Record, from the next step on, every contact touching one of ``geoms`` in
        ``watch.contacts`` (replaced at each step). Steps cost nothing extra without watches."""
        watch = ContactWatch(geoms)
        self._watches.append(watch)
        for geom in watch.geoms:
            self._watched.setdefault(geom, []).append(watch)
        self._kernel_stale = True
        return watch

    def unwatch_contacts(self, watch: ContactWatch) -> None:
        """Stop recording for ``watch`` (no error if it was already removed)."""
        if watch not in self._watches:
            return
        watch._fill = None
        self._watches.remove(watch)
        for geom in watch.geoms:
            watches = self._watched.get(geom, [])
            if watch in watches:
                watches.remove(watch)
            if not watches:
                self._watched.pop(geom, None)
        self._kernel_stale = True

    def _record_contacts(self, contacts: Sequence[ode.Contact], geom1: ode.GeomObject, geom2: ode.GeomObject) -> None:
        for watched, other, sign in ((geom1, geom2, 1.0), (geom2, geom1, -1.0)):
            watches = self._watched.get(watched)
            if not watches:
                continue
            for contact in contacts:
                position, normal, depth, _, _ = contact.getContactGeomParams()
                # ODE's normal points out of geom2 into geom1.
                record = WatchedContact(
                    watched, other, position, (sign * normal[0], sign * normal[1], sign * normal[2]), depth
                )
                for watch in watches:
                    watch._contacts.append(record)

    # --- stepping ----------------------------------------------------------------
    def step(self) -> None:
        """Collide, then advance exactly one fixed time step."""
        for watch in self._watches:
            watch._contacts = []
        if self._kernel is not None:
            self._collide_in_kernel(self._kernel)
        else:
            self._collide_in_python()
        for hook in self._pre_step_hooks:
            hook()
        self._stepper(self.params.time_step)
        self._steps += 1
        for hook in self._post_step_hooks:
            hook()

    def _collide_in_kernel(self, kernel: ContactKernel) -> None:
        if self._kernel_stale:
            self._set_kernel_tables(kernel)
        self._contact_count = kernel.collide()
        for watch in self._watches:
            watch._fill = self._fill_watches

    def _fill_watches(self) -> None:
        """The last step's watched contacts, from the kernel into the watches that were there for it."""
        pending = [watch for watch in self._watches if watch._fill is not None]
        for watch in pending:
            watch._fill = None
        geoms = ode._geom_c2py_lut  # PyODE's own id -> geom table
        for geom_id, other_id, position, normal, depth in self._kernel.watched():
            geom, other = geoms.get(geom_id), geoms.get(other_id)
            if geom is None or other is None:  # deleted since the step
                continue
            record = WatchedContact(geom, other, position, normal, depth)
            for watch in self._watched.get(geom, ()):
                if watch in pending:
                    watch._contacts.append(record)

    def _set_kernel_tables(self, kernel: ContactKernel) -> None:
        """Hand the kernel what _collide_in_python reads: surfaces (equal ones share an index; 0 is the default),
        watched geoms, excluded body pairs, ground tests and spaces."""
        indices: Dict[SurfaceParams, int] = {self.params.default_surface: 0}
        geoms: Dict[int, Tuple[int, bool]] = {}
        for geom, surface in self._surfaces.items():
            geoms[geom._id()] = (indices.setdefault(surface, len(indices)), geom in self._watched)
        for geom in self._watched:
            geoms.setdefault(geom._id(), (0, True))
        surfaces = list(indices)
        for body in {body for pair in self._jointed for body in pair} - set(self._body_ids):
            self._body_ids[body] = kernel.body_id(body)
        kernel.set_tables(
            geoms,
            [[self._combine(a, b) for b in surfaces] for a in surfaces],
            [(self._body_ids[a], self._body_ids[b]) for a, b in self._jointed],
            self.ground._id(),
            [geom._id() for geom, _, _ in self._ground_tests] if self._has_ground else [],
            self.space._id(),
            [space._id() for space in self._self_colliding],
            self.params.max_contacts,
        )
        self._kernel_stale = False

    def _collide_in_python(self) -> None:
        self._contact_joints.clear()
        ground = self.ground
        watched = self._watched
        ground_watched = ground in watched
        collide = _collide
        for geom, body, pair in self._ground_tests if self._has_ground else ():
            contacts = collide(ground, geom)
            if contacts:
                if ground_watched or geom in watched:  # a bumper's watch leaves the wheels' contacts alone
                    self._record_contacts(contacts, ground, geom)
                self._add_contacts(contacts, None, body, pair, ground, geom)
        if self.space.getNumGeoms() > 1:
            self.space.collide(None, self._near)
        for space in self._self_colliding:
            space.collide(None, self._near)
        self._contact_count = len(self._contact_joints)

    def _near(self, _data: object, geom1: ode.GeomObject, geom2: ode.GeomObject) -> None:
        if geom1.isSpace() or geom2.isSpace():
            ode.collide2(geom1, geom2, None, self._near)
            return
        body1 = geom1.getBody()
        body2 = geom2.getBody()
        if body1 is body2 or (body1, body2) in self._jointed:
            return
        contacts = _collide(geom1, geom2)
        if contacts:
            if self._watched:
                self._record_contacts(contacts, geom1, geom2)
            self._add_contacts(contacts, body1, body2, self._pair_contact(geom1, geom2), geom1, geom2)

    def _combine(self, a: SurfaceParams, b: SurfaceParams) -> ContactSurface:
        p = self.params
        return combine_surfaces(a, b, p.time_step, p.contact_surface_layer, p.contact_max_correcting_vel)

    def _pair_contact(self, geom1: ode.GeomObject, geom2: ode.GeomObject) -> PairContact:
        key = (geom1, geom2)
        pair = self._pair_cache.get(key)
        if pair is None:
            default = self.params.default_surface
            pair = (
                self._combine(self._surfaces.get(geom1, default), self._surfaces.get(geom2, default)),
                isinstance(geom1, ode.GeomCylinder) or isinstance(geom2, ode.GeomCylinder),
            )
            self._pair_cache[key] = pair
        return pair

    def _add_contacts(
        self,
        contacts: Sequence[ode.Contact],
        body1: Optional[ode.Body],
        body2: Optional[ode.Body],
        pair: PairContact,
        geom1: ode.GeomObject,
        geom2: ode.GeomObject,
    ) -> None:
        """One contact joint per point (as contact_kernel.c's add_contacts, step for step)."""
        surface, merge_line = pair
        mode, side, adjust, mu, mu2, erp, cfm, slip1, slip2, min_depth, depth_cap, layer, fx, fy, fz = surface
        merged: Optional[ContactGeom] = None
        if merge_line and len(contacts) == 2:
            contacts, merged = _merge_line_contact(contacts)
        elif len(contacts) > self.params.max_contacts:
            contacts = contacts[: self.params.max_contacts]
        world, keep = self.world, self._contact_joints.append
        for contact in contacts:
            contact_mode = mode
            if adjust or side:
                position, normal, depth = merged if merged is not None else contact.getContactGeomParams()[:3]
                if adjust:
                    depth = depth - min_depth
                    if depth > depth_cap:
                        depth = depth_cap
                    contact.setContactGeomParams(position, normal, depth + layer)
                if side:
                    direction = _friction_direction((geom1 if side == 1 else geom2).getRotation(), (fx, fy, fz), normal)
                    if direction is not None:
                        contact_mode |= oc.CONTACT_FDIR1
                        contact.setFDir1(direction)
            contact.setMode(contact_mode)
            contact.setMu(mu)
            contact.setMu2(mu2)
            contact.setSoftERP(erp)
            contact.setSoftCFM(cfm)
            contact.setSlip1(slip1)
            contact.setSlip2(slip2)
            joint = ode.ContactJoint(world, None, getattr(contact, "ode_contact", contact))
            joint.attach(body1, body2)
            keep(joint)
