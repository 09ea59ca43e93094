"""ctypes binding of the cameras' ray caster (src/ray_kernel.c, built by catkin as libturtle_sim_ode_rays.so): the
same ray tests as sensors.raycast, one pixel at a time in C. Where the library is not built, ``library()`` is None
and the cameras cast their rays with numpy."""
from __future__ import annotations

import ctypes
import functools
import os
from typing import Dict, Iterable, Optional, Tuple

import numpy as np
import ode

from turtle_sim_ode.physics.contact_kernel import find_library
from turtle_sim_ode.physics.trimesh import MeshGeom

LIBRARY = "libturtle_sim_ode_rays.so"
STRIDE = 20  # doubles per primitive row (see src/ray_kernel.c)
BOX, SPHERE, CYLINDER, CAPSULE, PLANE = range(5)
RGB = Tuple[float, float, float]


@functools.lru_cache(maxsize=None)
def library() -> Optional[ctypes.CDLL]:
    """The loaded ray caster, or None if it is not built (searched once)."""
    lib = find_library(LIBRARY)
    if lib is None or not all(hasattr(lib, name) for name in ("tso_render", "tso_cloud")):
        return None
    double_p, float_p, byte_p = (ctypes.POINTER(t) for t in (ctypes.c_double, ctypes.c_float, ctypes.c_uint8))
    lib.tso_render.restype = ctypes.c_long
    lib.tso_render.argtypes = [ctypes.c_int, ctypes.c_int, double_p, double_p, ctypes.c_int, double_p]
    lib.tso_render.argtypes += [ctypes.c_int, ctypes.POINTER(Mesh)]
    lib.tso_render.argtypes += [ctypes.c_double] * 5 + [double_p, ctypes.c_double, double_p, double_p, float_p]
    lib.tso_render.argtypes += [byte_p, ctypes.c_int]
    lib.tso_cloud.restype = ctypes.c_long
    lib.tso_cloud.argtypes = [ctypes.c_int, ctypes.c_int, float_p, byte_p] + [ctypes.c_double] * 5
    lib.tso_cloud.argtypes += [float_p, byte_p, ctypes.c_int]
    return lib


def primitive_row(geom: ode.GeomObject, colour: RGB) -> Optional[np.ndarray]:
    """The geom as a row of the C table, None for shapes that are not primitives (trimeshes: see Mesh; rays)."""
    row = np.zeros(STRIDE)
    if isinstance(geom, ode.GeomPlane):
        normal, offset = geom.getParams()
        row[0], row[4:7], row[13] = PLANE, normal, offset
        row[16:19] = colour
        return row
    row[1:4] = geom.getPosition()
    row[4:13] = geom.getRotation()
    if isinstance(geom, ode.GeomBox):
        half = np.array(geom.getLengths()) / 2
        row[0], row[13:16], row[19] = BOX, half, np.linalg.norm(half)
    elif isinstance(geom, ode.GeomSphere):
        row[0], row[13], row[19] = SPHERE, geom.getRadius(), geom.getRadius()
    elif isinstance(geom, (ode.GeomCylinder, ode.GeomCapsule)):
        radius, length = geom.getParams()
        capsule = isinstance(geom, ode.GeomCapsule)
        row[0], row[13], row[14] = CAPSULE if capsule else CYLINDER, radius, length
        row[19] = np.hypot(radius, length / 2) + (radius if capsule else 0.0)
    else:
        return None
    row[16:19] = colour
    return row


class Mesh(ctypes.Structure):
    """src/ray_kernel.c's Mesh."""

    _fields_ = [
        ("pose", ctypes.POINTER(ctypes.c_double)),
        ("face_count", ctypes.c_int),
        ("vertices", ctypes.POINTER(ctypes.c_double)),
        ("faces", ctypes.POINTER(ctypes.c_uint32)),
    ]


def mesh_pose(geom: MeshGeom, colour: RGB) -> np.ndarray:
    """A mesh's row for Mesh.pose: position, rotation (world from mesh, row-major), colour."""
    return np.concatenate((geom.getPosition(), geom.getRotation(), colour)).astype(np.float64)


def _pointer(array: np.ndarray, kind: type) -> ctypes._Pointer:
    return array.ctypes.data_as(ctypes.POINTER(kind))


class RayCaster:
    """Calls tso_render for one camera's image size; ``render`` fills and returns (depth as float64, INFINITY where
    nothing is hit; depth as float32, NaN there; rgb): rays through the pixel centres of a pinhole (focal, cx, cy)."""

    def __init__(self, lib: ctypes.CDLL, width: int, height: int, threads: Optional[int] = None) -> None:
        """``threads``: how many bands of rows are cast at once (default: the CPUs this process may run on)."""
        self._lib = lib
        self.size = (width, height)
        self.threads = threads if threads is not None else len(os.sched_getaffinity(0))
        self.tests = 0  # ray tests made by the last render
        # Scratch and cloud buffers, reused frame after frame (fresh megabytes cost page faults every frame).
        self._distance = np.empty((height, width))
        self._depth_out = np.empty((height, width), dtype=np.float32)
        self._cloud = np.zeros((height, width, 32), dtype=np.uint8)  # tso_cloud leaves the padding as it is

    def render(
        self,
        geoms: Iterable[ode.GeomObject],
        colours: Dict[ode.GeomObject, RGB],
        default: RGB,
        origin: np.ndarray,
        rotation: np.ndarray,
        near: float,
        far: float,
        lens: Tuple[float, float, float],
        light: np.ndarray,
        ambient: float,
        sky: RGB,
    ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        geoms = list(geoms)
        rows = [row for row in (primitive_row(g, colours.get(g, default)) for g in geoms) if row is not None]
        table = np.ascontiguousarray(np.array(rows) if rows else np.zeros((0, STRIDE)))
        meshes = [g for g in geoms if isinstance(g, MeshGeom)]
        poses = [mesh_pose(mesh, colours.get(mesh, default)) for mesh in meshes]  # alive until tso_render returns
        mesh_table = (Mesh * len(meshes))(
            *(
                Mesh(
                    _pointer(pose, ctypes.c_double),
                    len(m.faces),
                    _pointer(m.vertices, ctypes.c_double),
                    _pointer(m.faces, ctypes.c_uint32),
                )
                for pose, m in zip(poses, meshes)
            )
        )
        width, height = self.size
        distance = self._distance
        depth = np.empty((height, width), dtype=np.float32)
        rgb = np.empty((height, width, 3), dtype=np.uint8)
        origin = np.ascontiguousarray(origin, dtype=np.float64)
        rotation = np.ascontiguousarray(rotation, dtype=np.float64)
        light = np.ascontiguousarray(light, dtype=np.float64)
        sky_array = np.array(sky, dtype=np.float64)
        double = ctypes.c_double
        self.tests = self._lib.tso_render(
            width,
            height,
            _pointer(origin, double),
            _pointer(rotation, double),
            len(rows),
            _pointer(table, double),
            len(meshes),
            mesh_table,
            near,
            far,
            *lens,
            _pointer(light, double),
            ambient,
            _pointer(sky_array, double),
            _pointer(distance, double),
            _pointer(depth, ctypes.c_float),
            _pointer(rgb, ctypes.c_uint8),
            self.threads,
        )
        return distance, depth, rgb

    def cloud(
        self, depth: np.ndarray, rgb: np.ndarray, lens: Tuple[float, float, float], cutoff: float, cutoff_max: float
    ) -> Tuple[np.ndarray, np.ndarray, int]:
        """tso_cloud: the depth image within the cutoffs, the cloud's bytes (H, W, 32) and how many points are NaN.
        The two arrays are overwritten by the next call."""
        width, height = self.size
        depth = np.ascontiguousarray(depth, dtype=np.float32)
        rgb = np.ascontiguousarray(rgb, dtype=np.uint8)
        depth_out, cloud = self._depth_out, self._cloud
        missing = self._lib.tso_cloud(
            width,
            height,
            _pointer(depth, ctypes.c_float),
            _pointer(rgb, ctypes.c_uint8),
            *lens,
            cutoff,
            cutoff_max,
            _pointer(depth_out, ctypes.c_float),
            _pointer(cloud, ctypes.c_uint8),
            self.threads,
        )
        return depth_out, cloud, missing
