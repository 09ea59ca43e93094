"""Rays against ODE's primitive shapes and triangles in numpy: many rays from one origin at once, for the cameras.

Each ``hit_*`` function takes the rays' origin and unit directions in the shape's own frame and returns, per ray,
the distance to the first surface it enters (inf: none within (t_min, inf); t_min a number or one per ray) and the
outward normal there. Rays that start inside a shape do not see it (its faces point away, as a renderer culls back
faces). Rays (nearly) parallel to a face divide by (nearly) zero: the infinities that come out are misses, so numpy
is not warned.
"""
from __future__ import annotations

from typing import Tuple

import numpy as np

from turtle_sim_ode.sensors.ray_kernel import BOX, CAPSULE, CYLINDER, SPHERE

Hits = Tuple[np.ndarray, np.ndarray]  # distances (M,), normals (M, 3)


def hit_box(origin: np.ndarray, dirs: np.ndarray, half: np.ndarray, t_min: float) -> Hits:
    """An axis-aligned box of half extents ``half`` centred at 0 (slab method)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        inverse = 1.0 / dirs
        t1 = (-half - origin) * inverse
        t2 = (half - origin) * inverse
    near = np.fmin(t1, t2)
    far = np.fmax(t1, t2)
    axis = np.argmax(near, axis=1)
    t_near = near[np.arange(len(dirs)), axis]
    t_far = np.min(far, axis=1)
    hit = (t_near <= t_far) & (t_near > t_min)
    t = np.where(hit, t_near, np.inf)
    normals = np.zeros_like(dirs)
    rows = np.arange(len(dirs))
    normals[rows, axis] = -np.sign(dirs[rows, axis])
    return t, normals


def hit_sphere(origin: np.ndarray, dirs: np.ndarray, radius: float, t_min: float) -> Hits:
    b = dirs @ origin
    c = float(origin @ origin) - radius * radius
    disc = b * b - c
    with np.errstate(invalid="ignore"):
        t = -b - np.sqrt(disc)
    hit = (disc >= 0) & (t > t_min)
    t = np.where(hit, t, np.inf)
    points = origin + dirs * np.where(hit, t, 0.0)[:, None]
    return t, points / radius


def _side(origin: np.ndarray, dirs: np.ndarray, radius: float, half_length: float, t_min: float) -> Hits:
    """The curved side of a cylinder along z."""
    dx, dy = dirs[:, 0], dirs[:, 1]
    a = dx * dx + dy * dy
    b = dx * origin[0] + dy * origin[1]
    c = origin[0] ** 2 + origin[1] ** 2 - radius * radius
    disc = b * b - a * c
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = (-b - np.sqrt(disc)) / a
        z = origin[2] + t * dirs[:, 2]
        hit = (disc >= 0) & (a > 0) & (t > t_min) & (np.abs(z) <= half_length)
    t = np.where(hit, t, np.inf)
    normals = np.zeros_like(dirs)
    safe = np.where(hit, t, 0.0)
    normals[:, 0] = (origin[0] + safe * dx) / radius
    normals[:, 1] = (origin[1] + safe * dy) / radius
    return t, normals


def _closest(first: Hits, second: Hits) -> Hits:
    nearer = second[0] < first[0]
    return np.where(nearer, second[0], first[0]), np.where(nearer[:, None], second[1], first[1])


def hit_cylinder(origin: np.ndarray, dirs: np.ndarray, radius: float, length: float, t_min: float) -> Hits:
    """A cylinder along z, centred at 0 (ODE's GeomCylinder)."""
    half = length / 2
    best = _side(origin, dirs, radius, half, t_min)
    for sign in (1.0, -1.0):
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            t = (sign * half - origin[2]) / dirs[:, 2]
            x = origin[0] + t * dirs[:, 0]
            y = origin[1] + t * dirs[:, 1]
            hit = (t > t_min) & (x * x + y * y <= radius * radius) & (dirs[:, 2] * sign < 0)
        normals = np.zeros_like(dirs)
        normals[:, 2] = sign
        best = _closest(best, (np.where(hit, t, np.inf), normals))
    return best


def hit_capsule(origin: np.ndarray, dirs: np.ndarray, radius: float, length: float, t_min: float) -> Hits:
    """A capsule along z: a cylinder of ``length`` with a hemisphere at each end (ODE's GeomCapsule)."""
    half = length / 2
    best = _side(origin, dirs, radius, half, t_min)
    for sign in (1.0, -1.0):
        centre = np.array([0.0, 0.0, sign * half])
        best = _closest(best, hit_sphere(origin - centre, dirs, radius, t_min))
    return best


def hit_plane(origin: np.ndarray, dirs: np.ndarray, normal: np.ndarray, offset: float, t_min: float) -> Hits:
    """The plane normal . p = offset (world frame), seen from its front side only."""
    facing = dirs @ normal
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        t = (offset - float(normal @ origin)) / facing
    hit = (facing < 0) & (t > t_min)
    return np.where(hit, t, np.inf), np.broadcast_to(normal, dirs.shape)


def hit_triangle(origin: np.ndarray, dirs: np.ndarray, corners: np.ndarray, t_min: float) -> Hits:
    """A triangle (``corners`` (3, 3), world frame) from either side (Moller-Trumbore); the normal faces ``origin``."""
    edge1, edge2 = corners[1] - corners[0], corners[2] - corners[0]
    normal = np.cross(edge1, edge2)
    length = float(np.linalg.norm(normal))
    if not length > 0.0:
        return np.full(len(dirs), np.inf), np.zeros_like(dirs)
    to_origin = origin - corners[0]
    normal = normal / length * (1.0 if normal @ to_origin >= 0 else -1.0)
    p = np.cross(dirs, edge2)
    det = p @ edge1
    q = np.cross(to_origin, edge1)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        inverse = 1.0 / det
        a = (p @ to_origin) * inverse
        b = (dirs @ q) * inverse
        t = float(edge2 @ q) * inverse
        hit = (det != 0) & (a >= 0) & (b >= 0) & (a + b <= 1) & (t > t_min)
    return np.where(hit, t, np.inf), np.broadcast_to(normal, dirs.shape)


def mesh_triangles(pose: np.ndarray, vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """A mesh's triangles' corners in the world, (M, 3, 3), from its pose (sensors.ray_kernel.mesh_pose)."""
    rotation = pose[3:12].reshape(3, 3)
    return (vertices @ rotation.T + pose[:3])[faces]


class Primitive:
    """A row of the ray kernel's table (sensors.ray_kernel.shape_row) as the numpy caster sees it: its pose in the
    world, its bounding radius, its colour and a ``hit`` in its frame."""

    def __init__(self, row: np.ndarray) -> None:
        self.position = row[1:4]
        self.rotation = row[4:13].reshape(3, 3)  # world from shape
        self.radius = float(row[19])
        self.colour = tuple(row[16:19])
        kind, sizes = int(row[0]), row[13:16]
        if kind == BOX:
            self._hit = lambda o, d, t_min: hit_box(o, d, sizes, t_min)
        elif kind == SPHERE:
            self._hit = lambda o, d, t_min: hit_sphere(o, d, sizes[0], t_min)
        elif kind in (CYLINDER, CAPSULE):
            hit = hit_cylinder if kind == CYLINDER else hit_capsule
            self._hit = lambda o, d, t_min: hit(o, d, sizes[0], sizes[1], t_min)
        else:
            raise TypeError(f"no ray test for shape kind {kind}")

    def hit(self, origin: np.ndarray, dirs: np.ndarray, t_min: float) -> Hits:
        """Distances and world normals of rays from ``origin`` along unit world ``dirs`` (M, 3)."""
        local_origin = (origin - self.position) @ self.rotation
        t, normals = self._hit(local_origin, dirs @ self.rotation, t_min)
        return t, normals @ self.rotation.T
