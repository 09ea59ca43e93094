"""ODE triangle-mesh geoms through ctypes: Debian's python3-pyode is built without trimesh support
(ode.TriMeshData raises NotImplementedError), while its libode has it (dGetConfiguration: ODE_EXT_trimesh).

A MeshGeom is an ODE trimesh geom in a PyODE space, registered in PyODE's own id -> geom table so that space
callbacks hand it over like any geom; ``collide`` stands in for ode.collide where one side is a mesh (same dCollide
call, same points, so the contact kernel and the Python path stay bitwise alike). Meshes are body-less: they serve
static models (world walls, obstacles)."""
from __future__ import annotations

import ctypes
import ctypes.util
from typing import Any, List, Optional, Sequence, Tuple

import numpy
import ode


def _libode() -> Optional[ctypes.CDLL]:
    """The libode that PyODE is linked against (already loaded, so the same globals), if it can be found."""
    for name in ("libode.so.8", ctypes.util.find_library("ode")):
        if name:
            try:
                return ctypes.CDLL(name)
            except OSError:
                continue
    return None


LIBODE = _libode()
# PyODE's ode.collide asks ODE for at most this many points (as the contact kernel does).
MAX_POINTS = 150


class _ContactGeom(ctypes.Structure):
    _fields_ = [
        ("pos", ctypes.c_double * 4),
        ("normal", ctypes.c_double * 4),
        ("depth", ctypes.c_double),
        ("g1", ctypes.c_void_p),
        ("g2", ctypes.c_void_p),
        ("side1", ctypes.c_int),
        ("side2", ctypes.c_int),
    ]


def _declare(lib: Optional[ctypes.CDLL]) -> Optional[ctypes.CDLL]:
    if lib is None:
        return None
    p, i = ctypes.c_void_p, ctypes.c_int
    signatures = {
        "dGeomTriMeshDataCreate": (p, []),
        "dGeomTriMeshDataDestroy": (None, [p]),
        "dGeomTriMeshDataBuildDouble": (None, [p, p, i, i, p, i, i]),
        "dCreateTriMesh": (p, [p, p, p, p, p]),
        "dGeomDestroy": (None, [p]),
        "dGeomSetPosition": (None, [p, ctypes.c_double, ctypes.c_double, ctypes.c_double]),
        "dGeomSetQuaternion": (None, [p, ctypes.POINTER(ctypes.c_double)]),
        "dGeomGetPosition": (ctypes.POINTER(ctypes.c_double), [p]),
        "dGeomGetQuaternion": (None, [p, ctypes.POINTER(ctypes.c_double)]),
        "dGeomGetRotation": (ctypes.POINTER(ctypes.c_double), [p]),
        "dGeomGetAABB": (None, [p, ctypes.POINTER(ctypes.c_double)]),
        "dGeomGetBody": (p, [p]),
        "dBodyGetWorld": (p, [p]),
        "dWorldSetQuickStepW": (None, [p, ctypes.c_double]),
        "dWorldGetQuickStepW": (ctypes.c_double, [p]),
        "dCollide": (i, [p, p, i, ctypes.POINTER(_ContactGeom), i]),
    }
    for name, (restype, argtypes) in signatures.items():
        function = getattr(lib, name)
        function.restype = restype
        function.argtypes = argtypes
    return lib


_ODE = _declare(_libode())  # a handle of its own: its function signatures are set here
_POINTS = (_ContactGeom * MAX_POINTS)()


def world_id(world: ode.World) -> int:
    """The dWorldID of a PyODE World, which gives none: through a probe body's geom."""
    body = ode.Body(world)
    probe = ode.GeomSphere(None, 1.0)
    probe.setBody(body)
    found = _ODE.dBodyGetWorld(_ODE.dGeomGetBody(probe._id()))
    probe.setBody(None)
    return found


def set_quickstep_w(world: ode.World, w: float) -> None:
    """ODE's dWorldSetQuickStepW (Gazebo's <sor>), which PyODE does not bind; nothing without libode."""
    if _ODE is not None:
        _ODE.dWorldSetQuickStepW(world_id(world), float(w))


def quickstep_w(world: ode.World) -> float:
    return _ODE.dWorldGetQuickStepW(world_id(world))


def available() -> bool:
    return _ODE is not None


class TriMeshData:
    """ODE's trimesh data (its collision tree) of vertices and faces, built apart from any world or space: the spawn
    service builds it before it takes the world lock (0.3 s for 190,000 triangles), so that only the geom is made
    under it. The first MeshGeom made of it takes it over; data not taken is freed with this object."""

    def __init__(self, vertices: Sequence[Sequence[float]], faces: Sequence[Sequence[int]]):
        if _ODE is None:
            raise RuntimeError("libode cannot be loaded through ctypes: meshes are not available")
        # ODE keeps pointers to these arrays: they live as long as the data.
        self.vertices = numpy.ascontiguousarray(vertices, dtype=numpy.float64).reshape(-1, 3)
        self.faces = numpy.ascontiguousarray(faces, dtype=numpy.uint32).reshape(-1, 3)
        self._handle = _ODE.dGeomTriMeshDataCreate()
        _ODE.dGeomTriMeshDataBuildDouble(
            self._handle,
            self.vertices.ctypes.data,
            3 * 8,
            len(self.vertices),
            self.faces.ctypes.data,
            self.faces.size,
            3 * 4,
        )

    def take(self) -> "TriMeshData":
        """This data for a new geom the first time; a fresh copy of it after that (a geom frees what it takes)."""
        if self._handle is None:
            return TriMeshData(self.vertices, self.faces)
        taken = TriMeshData.__new__(TriMeshData)
        taken.vertices, taken.faces, taken._handle = self.vertices, self.faces, self._handle
        self._handle = None
        return taken

    def release(self) -> None:
        if self._handle is not None and _ODE is not None:
            _ODE.dGeomTriMeshDataDestroy(self._handle)
        self._handle = None

    def __del__(self) -> None:
        self.release()


class MeshGeom:
    """A body-less ODE trimesh in ``space`` (vertices and faces as ode.TriMeshData.build takes them, or ``prepared``
    data of them). Destroy it with ``destroy`` (not space.remove, which takes PyODE geoms only)."""

    def __init__(
        self,
        space: Optional[ode.SpaceBase],
        vertices: Sequence[Sequence[float]],
        faces: Sequence[Sequence[int]],
        prepared: Optional[TriMeshData] = None,
    ):
        data = prepared.take() if prepared is not None else TriMeshData(vertices, faces)
        self._vertices, self._faces = data.vertices, data.faces
        self._data, data._handle = data._handle, None  # this geom frees it
        self._gid = _ODE.dCreateTriMesh(space._id() if space is not None else None, self._data, None, None, None)
        ode._geom_c2py_lut[self._gid] = self  # so that PyODE's space callbacks and getGeom hand over this object

    # --- what PhysicsWorld, the builder and the sensors ask of a geom -----------------------------------------
    def _id(self) -> int:
        return self._gid

    def isSpace(self) -> bool:  # noqa: N802 (PyODE's names)
        return False

    def getBody(self) -> None:  # noqa: N802
        return None

    def setPosition(self, position: Sequence[float]) -> None:  # noqa: N802
        _ODE.dGeomSetPosition(self._gid, *map(float, position))

    def setQuaternion(self, quaternion: Sequence[float]) -> None:  # noqa: N802
        _ODE.dGeomSetQuaternion(self._gid, (ctypes.c_double * 4)(*map(float, quaternion)))

    def getPosition(self) -> Tuple[float, float, float]:  # noqa: N802
        position = _ODE.dGeomGetPosition(self._gid)
        return (position[0], position[1], position[2])

    def getQuaternion(self) -> Tuple[float, float, float, float]:  # noqa: N802
        quaternion = (ctypes.c_double * 4)()
        _ODE.dGeomGetQuaternion(self._gid, quaternion)
        return tuple(quaternion)  # type: ignore[return-value]

    def getRotation(self) -> Tuple[float, ...]:  # noqa: N802
        """World from mesh, 9 numbers row-major, as PyODE's (ODE keeps a 3 x 4 matrix)."""
        matrix = _ODE.dGeomGetRotation(self._gid)
        return tuple(matrix[row * 4 + column] for row in range(3) for column in range(3))

    @property
    def vertices(self) -> numpy.ndarray:
        """(N, 3) float64 in the mesh's frame (ODE's own copy: do not change it)."""
        return self._vertices

    @property
    def faces(self) -> numpy.ndarray:
        """(M, 3) uint32 vertex indices."""
        return self._faces

    def getAABB(self) -> Tuple[float, float, float, float, float, float]:  # noqa: N802
        box = (ctypes.c_double * 6)()
        _ODE.dGeomGetAABB(self._gid, box)
        return tuple(box)  # type: ignore[return-value]

    def destroy(self) -> None:
        """Remove from its space and free (idempotent)."""
        if self._gid:
            ode._geom_c2py_lut.pop(self._gid, None)
            _ODE.dGeomDestroy(self._gid)
            _ODE.dGeomTriMeshDataDestroy(self._data)
            self._gid = self._data = None


class MeshContact:
    """A contact point of a pair with a mesh, as ode.Contact for PhysicsWorld (PyODE's own cannot name a mesh as
    its geom, and reading back one without geoms fails): the point, and the ode.Contact the joint is made from."""

    __slots__ = ("ode_contact", "_geom")

    def __init__(self, position: Tuple[float, float, float], normal: Tuple[float, float, float], depth: float):
        self.ode_contact = ode.Contact()
        self.setContactGeomParams(position, normal, depth)

    def getContactGeomParams(self) -> Tuple[Any, Any, float, None, None]:  # noqa: N802
        position, normal, depth = self._geom
        return position, normal, depth, None, None

    def setContactGeomParams(self, position, normal, depth, *_geoms) -> None:  # noqa: N802
        self._geom = (tuple(position), tuple(normal), depth)
        self.ode_contact.setContactGeomParams(position, normal, depth)

    def __getattr__(self, name: str) -> Any:  # setMode, setMu, ... on the ode.Contact
        return getattr(self.ode_contact, name)


def collide(geom1: Any, geom2: Any) -> List[Any]:
    """ode.collide, also where either geom is a MeshGeom (then MeshContacts, from the same dCollide call)."""
    if not isinstance(geom1, MeshGeom) and not isinstance(geom2, MeshGeom):
        return ode.collide(geom1, geom2)
    count = _ODE.dCollide(geom1._id(), geom2._id(), MAX_POINTS, _POINTS, ctypes.sizeof(_ContactGeom))
    return [
        MeshContact(tuple(point.pos[:3]), tuple(point.normal[:3]), point.depth)
        for point in (_POINTS[index] for index in range(count))
    ]


def remove_geom(space: ode.SpaceBase, geom: Any) -> None:
    """space.remove for PyODE geoms, destroy for meshes."""
    if isinstance(geom, MeshGeom):
        geom.destroy()
    else:
        space.remove(geom)
