"""ctypes binding of the compiled contact kernel (src/contact_kernel.c, built by catkin as
libturtle_sim_ode_contacts.so): PhysicsWorld.step's collision and contact joints without Python's per-contact cost.

The kernel steps a world bitwise like physics.world's Python path (test_contact_kernel.py), which stays in use where
the library is not built or cannot be loaded (``ContactKernel.load`` returns None).
"""
from __future__ import annotations

import ctypes
import functools
import os
import struct
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple

import ode

LIBRARY = "libturtle_sim_ode_contacts.so"
DJOINT_TYPE_HINGE, DJOINT_TYPE_SLIDER = 2, 3  # ODE's dJointType values (ode/common.h)

# As physics.surfaces.ContactSurface: (mode, fdir_side, adjust_depth, mu, mu2, soft_erp, soft_cfm, slip1, slip2,
# min_depth, depth_cap, surface_layer, fdir1 x, y, z).
PairSurface = Tuple[int, int, int, float, float, float, float, float, float, float, float, float, float, float, float]
# (geom id, other geom id, position, normal from other towards geom, depth)
WatchedPoint = Tuple[int, int, Tuple[float, float, float], Tuple[float, float, float], float]


class _PairSurface(ctypes.Structure):
    _fields_ = [
        ("mode", ctypes.c_int),
        ("fdir_side", ctypes.c_int),
        ("adjust_depth", ctypes.c_int),
        ("mu", ctypes.c_double),
        ("mu2", ctypes.c_double),
        ("soft_erp", ctypes.c_double),
        ("soft_cfm", ctypes.c_double),
        ("slip1", ctypes.c_double),
        ("slip2", ctypes.c_double),
        ("min_depth", ctypes.c_double),
        ("depth_cap", ctypes.c_double),
        ("surface_layer", ctypes.c_double),
        ("fdir1_x", ctypes.c_double),  # the C struct's double fdir1[3]: the same layout
        ("fdir1_y", ctypes.c_double),
        ("fdir1_z", ctypes.c_double),
    ]


class _WatchedContact(ctypes.Structure):
    _fields_ = [
        ("geom", ctypes.c_void_p),
        ("other", ctypes.c_void_p),
        ("position", ctypes.c_double * 3),
        ("normal", ctypes.c_double * 3),
        ("depth", ctypes.c_double),
    ]


# _WatchedContact as struct sees it (native sizes and alignment, as the C compiler laid it out).
_WATCHED_LAYOUT = struct.Struct("@PP7d")
assert _WATCHED_LAYOUT.size == ctypes.sizeof(_WatchedContact)


def find_library(name: str = LIBRARY) -> Optional[ctypes.CDLL]:
    """A library of the package (the kernel by default) from the loader's path (catkin's setup puts devel/lib and
    install/lib on LD_LIBRARY_PATH), else from each CMAKE_PREFIX_PATH entry's lib/."""
    candidates = [name] + [
        os.path.join(prefix, "lib", name) for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(":") if prefix
    ]
    for candidate in candidates:
        try:
            return ctypes.CDLL(candidate)
        except OSError:
            continue
    return None


def _declare(lib: ctypes.CDLL) -> ctypes.CDLL:
    pointer, integer, pointers = ctypes.c_void_p, ctypes.c_int, ctypes.POINTER(ctypes.c_void_p)
    doubles = ctypes.POINTER(ctypes.c_double)
    signatures = {
        "tso_kernel_create": (pointer, []),
        "tso_kernel_destroy": (None, [pointer]),
        "tso_kernel_set_geoms": (
            integer,
            [pointer, integer, pointers, ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_ubyte)],
        ),
        "tso_kernel_set_pair_surfaces": (integer, [pointer, integer, ctypes.POINTER(_PairSurface)]),
        "tso_kernel_set_excluded": (integer, [pointer, integer, pointers]),
        "tso_kernel_set_ground_tests": (integer, [pointer, pointer, integer, pointers]),
        "tso_kernel_set_spaces": (integer, [pointer, pointer, integer, pointers, integer]),
        "tso_kernel_set_step": (None, [pointer, pointer, ctypes.c_double, integer]),
        "tso_kernel_step": (integer, [pointer]),
        "tso_kernel_watched": (ctypes.POINTER(_WatchedContact), [pointer, ctypes.POINTER(ctypes.c_int)]),
        "dGeomGetBody": (pointer, [pointer]),  # libode's, found through the kernel's dependencies
        "dBodyGetWorld": (pointer, [pointer]),
        "tso_joint_between": (pointer, [pointer, pointer, integer]),
        "tso_count_turns": (None, [integer, pointers, doubles, doubles]),
        "tso_damp_joints": (None, [integer, pointers, ctypes.POINTER(ctypes.c_ubyte), doubles]),
    }
    for name, (restype, argtypes) in signatures.items():
        function = getattr(lib, name)
        function.restype = restype
        function.argtypes = argtypes
    return lib


@functools.lru_cache(maxsize=None)
def library() -> Optional[ctypes.CDLL]:
    """The loaded kernel library, or None if it is not built (searched once)."""
    found = find_library()
    if found is None:
        return None
    try:
        return _declare(found)
    except AttributeError:  # an old build without every function
        return None


def _ids(values: Sequence[int]) -> ctypes.Array:
    return (ctypes.c_void_p * max(1, len(values)))(*values)


class ContactKernel:
    """One PhysicsWorld's kernel: its tables and the joint group of the last step's contact joints."""

    def __init__(self, lib: ctypes.CDLL) -> None:
        self._lib = lib
        self._handle = lib.tso_kernel_create()
        if not self._handle:
            raise MemoryError("tso_kernel_create")
        self._count = ctypes.c_int()
        self._step = lib.tso_kernel_step

    @property
    def library(self) -> ctypes.CDLL:
        return self._lib

    @classmethod
    def load(cls) -> Optional["ContactKernel"]:
        lib = library()
        return cls(lib) if lib is not None else None

    def __del__(self) -> None:
        handle, self._handle = getattr(self, "_handle", None), None
        if handle:
            self._lib.tso_kernel_destroy(handle)

    def set_tables(
        self,
        geoms: Dict[int, Tuple[int, bool]],
        pair_surfaces: Sequence[Sequence[PairSurface]],
        excluded: Iterable[Tuple[int, int]],
        ground: int,
        ground_tests: Sequence[int],
        top_space: int,
        self_colliding: Sequence[int],
        max_contacts: int,
    ) -> None:
        """``geoms``: geom id -> (surface index, watched); ``pair_surfaces``: the S x S table (rows) of the
        surfaces of index pairs; ``excluded``: body id pairs that never collide; ``ground_tests``: geom ids tested
        against the plane ``ground``, in order; then the spaces collided: ``top_space`` and the ``self_colliding``
        model spaces; at most ``max_contacts`` contact joints a pair (but line contacts, merged)."""
        lib, handle = self._lib, self._handle
        count = len(geoms)
        ids = _ids(list(geoms))
        surfaces = (ctypes.c_int * max(1, count))(*(surface for surface, _ in geoms.values()))
        watched = (ctypes.c_ubyte * max(1, count))(*(int(flag) for _, flag in geoms.values()))
        side = len(pair_surfaces)
        if side < 1 or any(len(row) != side for row in pair_surfaces):
            raise ValueError("the pair surface table is not square: %s rows" % side)
        table = (_PairSurface * (side * side))(*(_PairSurface(*entry) for row in pair_surfaces for entry in row))
        pairs = [body for pair in excluded for body in pair]
        results = (
            lib.tso_kernel_set_geoms(handle, count, ids, surfaces, watched),
            lib.tso_kernel_set_pair_surfaces(handle, side, table),
            lib.tso_kernel_set_excluded(handle, len(pairs) // 2, _ids(pairs)),
            lib.tso_kernel_set_ground_tests(handle, ground, len(ground_tests), _ids(list(ground_tests))),
            lib.tso_kernel_set_spaces(handle, top_space, len(self_colliding), _ids(self_colliding), max_contacts),
        )
        if any(results):
            raise MemoryError("the contact kernel could not store its tables")

    def set_step(self, world_id: int, time_step: float, quick: bool) -> None:
        """What ``step`` steps: the world ``world_id`` (see ``world_id``) by ``time_step`` with the quick solver or
        the world solver, as PyODE's World.quickStep or World.step would."""
        self._lib.tso_kernel_set_step(self._handle, world_id, time_step, int(quick))

    def step(self) -> int:
        """Destroy the last step's contact joints, make this step's, then step as set by ``set_step``; returns the
        contact joints made. The whole step is one ctypes call, which runs without the GIL (PyODE's World.step holds
        it): the node's other threads may run meanwhile (see the README's performance section)."""
        return self._step(self._handle)

    def world_id(self, world: ode.World) -> int:
        """The ODE id of a PyODE World (which has no ``_id`` either), read through a body made in it for the
        purpose and destroyed with its wrapper."""
        body = ode.Body(world)  # alive until its world is read
        return self._lib.dBodyGetWorld(self.body_id(body)) or 0

    def body_id(self, body: Any) -> int:
        """The ODE id of a PyODE Body (0 for None), read through a probe geom: PyODE gives bodies no ``_id``."""
        if body is None:
            return 0
        probe = ode.GeomSphere(None, 1.0)
        probe.setBody(body)
        body_id = self._lib.dGeomGetBody(probe._id())
        probe.setBody(None)
        return body_id

    def joint_id(self, joint: Any) -> int:
        """The ODE id of a PyODE HingeJoint or SliderJoint (PyODE gives joints no ``_id`` either): the one joint of its
        kind between its bodies, 0 if there is more than one."""
        kind = DJOINT_TYPE_SLIDER if isinstance(joint, ode.SliderJoint) else DJOINT_TYPE_HINGE
        return self._lib.tso_joint_between(self.body_id(joint.getBody(0)), self.body_id(joint.getBody(1)), kind) or 0

    def watched(self) -> List[WatchedPoint]:
        """Points of the last collide touching watched geoms."""
        points = self._lib.tso_kernel_watched(self._handle, ctypes.byref(self._count))
        data = ctypes.string_at(points, self._count.value * ctypes.sizeof(_WatchedContact))
        return [
            (geom, other, (px, py, pz), (nx, ny, nz), depth)
            for geom, other, px, py, pz, nx, ny, nz, depth in _WATCHED_LAYOUT.iter_unpack(data)
        ]
