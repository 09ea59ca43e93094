"""Textures on the cameras' pictures: a textured primitive is drawn white by the ray casters (so a pixel holds its
shading), then each pixel whose depth puts its surface point on it is multiplied by its texel. Boxes (and planes, drawn as
boxes) carry the whole image on each face, as Ogre's box mesh maps it: seen from outside, u runs along the face's
first axis and v down its second (+z face: u along +x, v along -y; -z face: u along +x, v along +y; +-x faces: u
along -+y, v along -z; +-y faces: u along +-x, v along -z). Spheres and cylinders wrap it once around z.

Per-pixel work is numpy over the pixels the shape may cover (CameraSensor._pixel_box)."""
from __future__ import annotations

from typing import Callable, List, Optional, Tuple

import numpy as np

from turtle_sim_ode.models.textures import texture_lookup
from turtle_sim_ode.sensors.ray_kernel import BOX, SPHERE
from turtle_sim_ode.sensors.raycast import Primitive

# A point from the depth buffer lies on a surface to rounding: tolerance relative to the depth.
SAME_SURFACE = 1e-6
PixelBox = Tuple[int, int, int, int]


def face_uv(local: np.ndarray, half: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Texture coordinates (0..1) of points ``local`` (N, 3) on the surface of a box of half extents ``half``
    centred at 0: on the face they lie on (the axis where |p| / half is largest)."""
    scaled = local / half
    axis = np.argmax(np.abs(scaled), axis=1)
    sign = np.sign(scaled[np.arange(len(local)), axis])
    x, y, z = scaled[:, 0], scaled[:, 1], scaled[:, 2]
    u = np.select([axis == 2, axis == 0], [x, -sign * y], sign * x)
    v = np.select([axis == 2], [-sign * y], -z)
    return (u + 1.0) / 2.0, (v + 1.0) / 2.0


def round_uv(local: np.ndarray, half_height: float) -> Tuple[np.ndarray, np.ndarray]:
    """Texture coordinates of points on a sphere or cylinder around z: u once around, v down its height."""
    u = (np.arctan2(local[:, 1], local[:, 0]) + np.pi) / (2.0 * np.pi)
    v = 0.5 - local[:, 2] / (2.0 * half_height)
    return u, v


def apply_textures(
    rgb: np.ndarray,
    depth: np.ndarray,
    textured: List[Tuple[np.ndarray, np.ndarray]],
    origin: np.ndarray,
    rotation: np.ndarray,
    lens: Tuple[np.ndarray, np.ndarray],
    pixel_box: Callable[[np.ndarray, float], Optional[PixelBox]],
) -> None:
    """Multiply ``rgb`` (H, W, 3) uint8, in place, by the texels of each textured primitive (row, image) where
    ``depth`` (optical z, float64; inf or NaN: nothing) puts the nearest surface on it. ``rotation``: world from
    optical; ``lens``: x / z of each column and y / z of each row; ``pixel_box(centre, radius)``: the pixels a
    sphere in the optical frame may cover. The surface points come from the depth alone (no second ray test)."""
    columns, rows = lens
    for row, image in textured:
        shape = Primitive(row)
        box = pixel_box((shape.position - origin) @ rotation, shape.radius)
        if box is None:
            continue
        i0, i1, j0, j1 = box
        z = depth[j0:j1, i0:i1]
        optical = np.stack(
            (np.broadcast_to(columns[None, i0:i1], z.shape) * z, rows[j0:j1, None] * z, z), axis=-1
        ).reshape(-1, 3)
        # shape frame from optical frame: local = S^T (origin + R p - position)
        local = optical @ (rotation.T @ shape.rotation) + (origin - shape.position) @ shape.rotation
        tolerance = SAME_SURFACE * (1.0 + np.abs(z.reshape(-1)))
        with np.errstate(invalid="ignore"):
            if int(row[0]) == BOX:
                half = np.asarray(row[13:16])
                outside = np.abs(local) - half
                mine = np.all(outside <= tolerance[:, None], axis=1) & (outside.max(axis=1) >= -tolerance)
            else:
                radius = float(row[13])
                mine = np.hypot(local[:, 0], local[:, 1]) <= radius + tolerance
                mine &= np.abs(local[:, 2]) <= (float(row[14]) / 2.0 if int(row[0]) != SPHERE else radius) + tolerance
        if not mine.any():
            continue
        if int(row[0]) == BOX:
            u, v = face_uv(local[mine], half)
        else:
            u, v = round_uv(local[mine], max(float(row[14]) / 2.0, float(row[13])))
        region = rgb[j0:j1, i0:i1].reshape(-1, 3)
        region[mine] = (region[mine] * texture_lookup(image, u, v) + 0.5).astype(np.uint8)
        rgb[j0:j1, i0:i1] = region.reshape(j1 - j0, i1 - i0, 3)
