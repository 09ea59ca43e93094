"""ODE world: collision spaces and geoms, a ground plane, the contacts of each step and a fixed-step clock."""
from __future__ import annotations

import ctypes
from typing import Callable, Dict, Iterable, List, Optional, Sequence, Set, Tuple

import ode

from turtle_sim_ode.physics.contact_kernel import ContactKernel
from turtle_sim_ode.physics.joint_batch import JointDamper, TurnCounter
from turtle_sim_ode.physics.contacts import ContactWatch, WatchedContact, add_contact_joints
from turtle_sim_ode.physics.settings import PhysicsParams, configure_world
from turtle_sim_ode.physics.surfaces import ContactSurface, PairContact, SurfaceParams, combine_surfaces, ground_surface
from turtle_sim_ode.physics.trimesh import LIBODE as _LIBODE
from turtle_sim_ode.physics.trimesh import collide as _collide
from turtle_sim_ode.physics.trimesh import remove_geom


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
        self._world_id = self._kernel.world_id(self.world) if self._kernel is not None else 0
        if not self._world_id:  # the world's id cannot be told: the Python path steps it
            self._kernel = None
        self._body_ids: Dict[ode.Body, int] = {}
        self._stepper = self.world.quickStep if p.solver == "quick" else self.world.step
        # sim_time = _time_base + _steps * time_step: exact, and continuous when time_step changes.
        self._time_base = 0.0
        self._steps = 0
        self._static_space: Optional[ode.SpaceBase] = None
        self._self_colliding: List[ode.SpaceBase] = []
        self._surfaces: Dict[ode.GeomObject, SurfaceParams] = {self.ground: ground_surface(p.ground_surface)}
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
        self._kernel_stale = True  # the kernel steps by the time step and with the solver it was last given
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
        self._surfaces[self.ground] = ground_surface(surface)
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

    def turn_counter(self, hinges: Sequence[ode.HingeJoint]) -> Optional[TurnCounter]:
        """A counter of ``hinges``' turns in the contact kernel's library (slot i: hinges[i]), None on the Python path
        or if a hinge's ODE id cannot be found."""
        ids = self._joint_ids(hinges)
        return TurnCounter(self._kernel.library, ids, hinges) if self._kernel is not None and all(ids) else None

    def joint_damper(self, damped: Sequence[Tuple[ode.Joint, float]]) -> Optional[JointDamper]:
        """Viscous damping of (hinge or slider, coefficient) pairs in the contact kernel's library, None on the Python
        path or if a joint's ODE id cannot be found."""
        joints = [joint for joint, _ in damped]
        ids = self._joint_ids(joints)
        if self._kernel is None or not all(ids):
            return None
        entries = [(i, isinstance(j, ode.SliderJoint), c) for i, (j, c) in zip(ids, damped)]
        return JointDamper(self._kernel.library, entries, joints)

    def _joint_ids(self, joints: Sequence[ode.Joint]) -> List[int]:
        kernel = self._kernel
        return [kernel.joint_id(joint) for joint in joints] if kernel is not None else []

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
            # The hooks come first here: they read the bodies' state and forces, which colliding does not change.
            for hook in self._pre_step_hooks:
                hook()
            self._step_in_kernel(self._kernel)
        else:
            self._collide_in_python()
            for hook in self._pre_step_hooks:
                hook()
            self._stepper(self.params.time_step)
        self._steps += 1
        for hook in self._post_step_hooks:
            hook()

    def _step_in_kernel(self, kernel: ContactKernel) -> None:
        """Collide and integrate in one call of the kernel, without the GIL (see ContactKernel.step)."""
        if self._kernel_stale:
            self._set_kernel_tables(kernel)
        self._contact_count = kernel.step()
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
        kernel.set_step(self._world_id, self.params.time_step, self.params.solver == "quick")
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
                add_contact_joints(
                    self.world, self._contact_joints, self.params.max_contacts, contacts, None, body, pair, ground, geom
                )
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
            add_contact_joints(
                self.world,
                self._contact_joints,
                self.params.max_contacts,
                contacts,
                body1,
                body2,
                self._pair_contact(geom1, geom2),
                geom1,
                geom2,
            )

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
