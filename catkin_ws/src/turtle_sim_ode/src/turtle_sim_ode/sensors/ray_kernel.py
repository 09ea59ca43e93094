"""ctypes binding of the cameras' and lidars' ray caster (src/ray_*.c, one file a part, see src/ray_kernel.h; built by
catkin as libturtle_sim_ode_rays.so): the same ray tests as sensors.raycast, one pixel at a time in C. Where the
library is not built, ``library()`` is None and the cameras cast their rays with numpy."""
from __future__ import annotations

import ctypes
import functools
import math
import os
from typing import Optional, Sequence, Tuple

import numpy as np
import ode

from turtle_sim_ode.physics.contact_kernel import find_library
from turtle_sim_ode.models.description import Box, Cylinder, Geometry, Sphere

LIBRARY = "libturtle_sim_ode_rays.so"
STRIDE = 20  # doubles per primitive row (see src/ray_kernel.h)
BOX, SPHERE, CYLINDER, CAPSULE, PLANE = range(5)
RGB = Tuple[float, float, float]


@functools.lru_cache(maxsize=None)
def library() -> Optional[ctypes.CDLL]:
    """The loaded ray caster, or None if it is not built (searched once)."""
    lib = find_library(LIBRARY)
    exported = ("tso_render", "tso_cloud", "tso_rays", "tso_velodyne_cloud")
    if lib is None or not all(hasattr(lib, name) for name in exported):
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
    lib.tso_rays.restype = ctypes.c_long
    lib.tso_rays.argtypes = [ctypes.c_int, double_p, double_p, double_p, ctypes.c_int, double_p, ctypes.c_int]
    lib.tso_rays.argtypes += [ctypes.POINTER(Mesh), double_p, ctypes.c_double, ctypes.c_double, double_p, ctypes.c_int]
    lib.tso_velodyne_cloud.restype = ctypes.c_long
    lib.tso_velodyne_cloud.argtypes = [ctypes.c_int, ctypes.c_int, double_p, double_p] + [ctypes.c_double] * 3
    lib.tso_velodyne_cloud.argtypes += [ctypes.c_int, ctypes.c_int, double_p, byte_p]
    return lib


def shape_row(
    kind: int, sizes: Sequence[float], position: Sequence[float], rotation: Sequence[float], colour: RGB
) -> np.ndarray:
    """A row of the C table: shape ``kind`` (BOX: half extents; SPHERE: radius; CYLINDER, CAPSULE: radius, length
    along z) at ``position``, ``rotation`` (world from shape, 9 numbers row-major), with its bounding radius."""
    row = np.zeros(STRIDE)
    row[0], row[1:4], row[4:13], row[16:19] = kind, position, rotation, colour
    row[13 : 13 + len(sizes)] = sizes
    if kind == BOX:
        row[19] = np.linalg.norm(sizes)
    elif kind == SPHERE:
        row[19] = sizes[0]
    else:
        radius, length = sizes
        row[19] = np.hypot(radius, length / 2) + (radius if kind == CAPSULE else 0.0)
    return row


def primitive_row(geom: ode.GeomObject, colour: RGB) -> Optional[np.ndarray]:
    """A collision geom as a row of the C table, None for shapes that are not primitives (trimeshes: see Mesh;
    rays)."""
    if isinstance(geom, ode.GeomPlane):
        normal, offset = geom.getParams()
        row = np.zeros(STRIDE)
        row[0], row[4:7], row[13], row[16:19] = PLANE, normal, offset, colour
        return row
    if isinstance(geom, ode.GeomBox):
        kind, sizes = BOX, np.array(geom.getLengths()) / 2
    elif isinstance(geom, ode.GeomSphere):
        kind, sizes = SPHERE, (geom.getRadius(),)
    elif isinstance(geom, (ode.GeomCylinder, ode.GeomCapsule)):
        kind, sizes = CAPSULE if isinstance(geom, ode.GeomCapsule) else CYLINDER, geom.getParams()
    else:
        return None
    return shape_row(kind, sizes, geom.getPosition(), geom.getRotation(), colour)


def visual_row(geometry: Geometry, position: Sequence[float], rotation: Sequence[float], colour: RGB) -> np.ndarray:
    """A box, sphere or cylinder visual at ``position``, ``rotation`` (as shape_row's) as a row of the C table."""
    if isinstance(geometry, Box):
        return shape_row(BOX, np.array(geometry.size) / 2, position, rotation, colour)
    if isinstance(geometry, Sphere):
        return shape_row(SPHERE, (geometry.radius,), position, rotation, colour)
    if isinstance(geometry, Cylinder):
        return shape_row(CYLINDER, (geometry.radius, geometry.length), position, rotation, colour)
    raise TypeError(f"no row for {type(geometry).__name__} (meshes: see Mesh)")


# A container's CPU quota, cgroup v2 then v1, as the container sees its own cgroup.
CPU_MAX = "/sys/fs/cgroup/cpu.max"  # "QUOTA PERIOD" or "max PERIOD"
CFS_QUOTA, CFS_PERIOD = "/sys/fs/cgroup/cpu/cpu.cfs_quota_us", "/sys/fs/cgroup/cpu/cpu.cfs_period_us"  # -1: none


def _read(path: str) -> Optional[str]:
    try:
        with open(path) as file:
            return file.read()
    except OSError:
        return None


def cpu_quota(cpu_max: str = CPU_MAX, cfs_quota: str = CFS_QUOTA, cfs_period: str = CFS_PERIOD) -> Optional[float]:
    """CPUs' worth of time the cgroup quota grants this process (docker --cpus), None without a quota."""
    text = _read(cpu_max)
    parts = text.split() if text is not None else [_read(cfs_quota) or "", _read(cfs_period) or ""]
    try:
        quota, period = float(parts[0]), float(parts[1])
    except (ValueError, IndexError):  # "max", missing files
        return None
    return quota / period if quota > 0 and period > 0 else None


def usable_cpus() -> int:
    """The CPUs this process may run on, fewer under a cgroup quota: threads beyond it would be throttled."""
    cpus = len(os.sched_getaffinity(0))
    quota = cpu_quota()
    return max(1, min(cpus, math.ceil(quota))) if quota is not None else cpus


class Mesh(ctypes.Structure):
    """src/ray_kernel.h's Mesh."""

    _fields_ = [
        ("pose", ctypes.POINTER(ctypes.c_double)),
        ("face_count", ctypes.c_int),
        ("vertices", ctypes.POINTER(ctypes.c_double)),
        ("faces", ctypes.POINTER(ctypes.c_uint32)),
    ]


def mesh_pose(position: Sequence[float], rotation: Sequence[float], colour: RGB) -> np.ndarray:
    """A mesh's row for Mesh.pose: position, rotation (world from mesh, 9 numbers row-major), colour."""
    return np.concatenate((position, rotation, colour)).astype(np.float64)


# What tso_render draws of a mesh: Mesh.pose (mesh_pose), vertices (N, 3) float64, faces (M, 3) uint32.
MeshItem = Tuple[np.ndarray, np.ndarray, np.ndarray]


def _pointer(array: np.ndarray, kind: type) -> ctypes._Pointer:
    return array.ctypes.data_as(ctypes.POINTER(kind))


def _mesh_table(meshes: Sequence[MeshItem]) -> Tuple[list, ctypes.Array]:
    """The meshes as C arrays (returned: they must live while the table is used) and their table of Mesh."""
    arrays = [
        (pose, np.ascontiguousarray(vertices, dtype=np.float64), np.ascontiguousarray(faces, dtype=np.uint32))
        for pose, vertices, faces in meshes
    ]
    table = (Mesh * len(arrays))(
        *(
            Mesh(
                _pointer(pose, ctypes.c_double),
                len(faces),
                _pointer(vertices, ctypes.c_double),
                _pointer(faces, ctypes.c_uint32),
            )
            for pose, vertices, faces in arrays
        )
    )
    return arrays, table


def cast_rays(
    lib: ctypes.CDLL,
    origin: np.ndarray,
    rotation: np.ndarray,
    directions: np.ndarray,
    table: np.ndarray,
    meshes: Sequence[MeshItem],
    t_min: float,
    t_max: float,
    threads: int,
) -> Tuple[np.ndarray, int]:
    """tso_rays: the distance along each unit ray (``directions``, (N, 3), in the frame that ``rotation`` (3 x 3)
    takes to the world's) from ``origin`` to its nearest hit on ``table``'s rows (planes too) and ``meshes`` within
    (t_min, t_max], t_max where there is none; and the ray tests made. The rays are turned in C: one call that lets
    go of the GIL (a lidar's thread takes it back once, not after a matmul and a clamp as well)."""
    directions = np.ascontiguousarray(directions, dtype=np.float64).reshape(-1, 3)
    table = np.ascontiguousarray(table, dtype=np.float64).reshape(-1, STRIDE)
    arrays, mesh_table = _mesh_table(meshes)
    radii = np.array(
        [float(np.sqrt((vertices**2).sum(axis=1).max())) if len(vertices) else 0.0 for _, vertices, _ in arrays]
    )
    radii = np.ascontiguousarray(radii, dtype=np.float64)
    origin = np.ascontiguousarray(origin, dtype=np.float64)
    rotation = np.ascontiguousarray(rotation, dtype=np.float64)
    distance = np.empty(len(directions))
    double = ctypes.c_double
    tests = lib.tso_rays(
        len(directions),
        _pointer(origin, double),
        _pointer(rotation, double),
        _pointer(directions, double),
        len(table),
        _pointer(table, double),
        len(arrays),
        mesh_table,
        _pointer(radii, double),
        t_min,
        t_max,
        _pointer(distance, double),
        threads,
    )
    return distance, tests


def velodyne_cloud(
    lib: ctypes.CDLL,
    ranges: np.ndarray,
    noise: Tuple[Optional[np.ndarray], float],
    band: Tuple[float, float],
    organised: bool,
    intensity_kept: bool,
    directions: np.ndarray,
    points: np.ndarray,
) -> int:
    """tso_velodyne_cloud: a Velodyne's points of the scan ``ranges`` (rings, azimuths) into ``points`` (a record
    array with room for every ray, POINT_STEP bytes each); ``noise``: standard normals (azimuths, rings) or None,
    and the gaussianNoise they are scaled by; ``directions`` (azimuths, rings, 3) contiguous. Returns how many points
    were written."""
    azimuths, rings = directions.shape[:2]
    ranges = np.ascontiguousarray(ranges, dtype=np.float64)
    normals, sigma = noise
    double = ctypes.c_double
    return lib.tso_velodyne_cloud(
        azimuths,
        rings,
        _pointer(ranges, double),
        None if normals is None else _pointer(normals, double),
        sigma,
        band[0],
        band[1],
        int(organised),
        int(intensity_kept),
        _pointer(directions, double),
        _pointer(points, ctypes.c_uint8),
    )


class RayCaster:
    """Calls tso_render for one camera's image size; ``render`` fills and returns (depth as float64, INFINITY where
    nothing is hit; depth as float32, NaN there; rgb): rays through the pixel centres of a pinhole (focal, cx, cy)."""

    def __init__(self, lib: ctypes.CDLL, width: int, height: int, threads: Optional[int] = None) -> None:
        """``threads``: how many bands of rows are cast at once (default: usable_cpus())."""
        self._lib = lib
        self.size = (width, height)
        self.threads = threads if threads is not None else usable_cpus()
        self.tests = 0  # ray tests made by the last render
        # Scratch and cloud buffers, reused frame after frame (fresh megabytes cost page faults every frame).
        self._distance = np.empty((height, width))
        self._depth_out = np.empty((height, width), dtype=np.float32)
        self._cloud = np.zeros((height, width, 32), dtype=np.uint8)  # tso_cloud leaves the padding as it is

    def render(
        self,
        table: np.ndarray,
        meshes: Sequence[MeshItem],
        origin: np.ndarray,
        rotation: np.ndarray,
        near: float,
        far: float,
        lens: Tuple[float, float, float],
        light: np.ndarray,
        ambient: float,
        sky: RGB,
    ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Cast the rays at ``table`` (rows of shape_row or primitive_row, tested in their order) and ``meshes``."""
        table = np.ascontiguousarray(table, dtype=np.float64).reshape(-1, STRIDE)
        meshes, mesh_table = _mesh_table(meshes)  # the arrays alive until tso_render returns
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
            len(table),
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
