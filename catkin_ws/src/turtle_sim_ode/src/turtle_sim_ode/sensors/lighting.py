"""The world's point, spot and further directional lights on a camera's picture, per pixel, as gazebo-classic's
default lighting (Ogre's RTShader per-pixel lighting, SGXLib_PerPixelLighting: SGX_Light_*_Diffuse) adds each light's
diffuse term: diffuse colour x max(0, n . l) x attenuation x spot factor, with

- attenuation 1 / (constant + linear d + quadratic d^2) within ``range`` of the light, nothing beyond it; gazebo's
  rendering::Light::SetAttenuation clamps constant and linear to [0, 1] before Ogre sees them;
- the spot factor clamp((rho - cos(outer / 2)) / (cos(inner / 2) - cos(outer / 2)), 0, 1) ^ falloff, rho the cosine
  between the spot's axis and the ray from the light to the point (Ogre's PerPixelLighting passes the cosines of the
  half angles of setSpotlightRange's inner and outer angles); beyond the outer cone nothing.

The ray casters shade each surface with ambient light and one directional light (the sun: colour x (AMBIENT +
(1 - AMBIENT) max(0, n . sun))). ``relight`` adds the other lights to what they drew without a second cast: each
pixel's surface point comes from the depth (origin + depth along the pixel's ray), its normal from its neighbours'
points (on each image axis the neighbour nearer in depth, so an edge does not bend it), and the pixel is scaled by
shade_all / shade_sun, shade_all = AMBIENT + (1 - AMBIENT) min(1, sun term + the other lights' terms) per channel
(Ogre clamps the lights' sum to 1). No shadows: a light reaches every surface facing it within its range."""
from __future__ import annotations

from dataclasses import dataclass
from typing import List, Sequence, Tuple

import numpy as np

from turtle_sim_ode.models.lights import Light
from turtle_sim_ode.models.transforms import quat_matrix

# An attenuation denominator at or below this (constant = linear = 0 near the light) is taken as this: Ogre's 1 / 0
# is infinite, and the clamp of the lights' sum makes it full light either way.
SMALLEST_DENOMINATOR = 1e-6


@dataclass(frozen=True)
class PixelLight:
    """A light as the shading takes it (world frame): ``kind`` 'directional', 'point' or 'spot'; ``toward`` the
    unit direction it shines; ``diffuse`` r, g, b (negatives as 0); ``attenuation`` range, constant, linear,
    quadratic (Light.cc's clamps applied); ``spot`` cos(inner / 2), cos(outer / 2), falloff."""

    kind: str
    position: np.ndarray
    toward: np.ndarray
    diffuse: np.ndarray
    attenuation: Tuple[float, float, float, float]
    spot: Tuple[float, float, float]

    @staticmethod
    def of(light: Light) -> "PixelLight":
        (x, y, z), (qx, qy, qz, qw) = light.pose
        direction = np.asarray(light.direction, dtype=float)
        norm = float(np.linalg.norm(direction))
        toward = np.asarray(quat_matrix((qw, qx, qy, qz))) @ (direction / norm if norm > 0 else direction)
        clamp = lambda value: min(max(value, 0.0), 1.0)  # noqa: E731
        return PixelLight(
            light.type,
            np.array((x, y, z), dtype=float),
            toward,
            np.maximum(np.asarray(light.diffuse[:3], dtype=float), 0.0),
            (
                light.attenuation_range,
                clamp(light.attenuation_constant),
                clamp(light.attenuation_linear),
                light.attenuation_quadratic,
            ),
            (np.cos(light.spot_inner_angle / 2.0), np.cos(light.spot_outer_angle / 2.0), light.spot_falloff),
        )


def attenuation(distance: np.ndarray, range_: float, constant: float, linear: float, quadratic: float) -> np.ndarray:
    """Ogre's 1 / (constant + linear d + quadratic d^2) within ``range_``, 0 beyond."""
    denominator = np.maximum(constant + linear * distance + quadratic * distance * distance, SMALLEST_DENOMINATOR)
    return np.where(distance <= range_, 1.0 / denominator, 0.0)


def spot_factor(rho: np.ndarray, cos_inner: float, cos_outer: float, falloff: float) -> np.ndarray:
    """Ogre's spot term of the cosine ``rho`` off the spot's axis: 1 inside the inner cone, 0 beyond the outer one,
    ((rho - cos_outer) / (cos_inner - cos_outer)) ^ falloff between (a cone without a rim where inner >= outer)."""
    width = cos_inner - cos_outer
    if width <= 0.0:
        return (rho > cos_outer).astype(float)
    edge = np.clip((rho - cos_outer) / width, 0.0, 1.0)
    return np.where(edge > 0.0, edge ** max(falloff, 0.0), 0.0)


def light_terms(points: np.ndarray, normals: np.ndarray, lights: Sequence[PixelLight]) -> np.ndarray:
    """The lights' summed diffuse terms (N, 3) at ``points`` (N, 3) of unit ``normals`` (zero: unlit), unclamped."""
    total = np.zeros(points.shape[:-1] + (3,))
    for light in lights:
        if light.kind == "directional":
            factor = np.maximum(normals @ -light.toward, 0.0)
        else:
            to_light = light.position - points
            distance = np.sqrt(np.einsum("...i,...i->...", to_light, to_light))
            unit = to_light / np.maximum(distance, 1e-12)[..., None]
            factor = np.maximum(np.einsum("...i,...i->...", normals, unit), 0.0) * attenuation(
                distance, *light.attenuation
            )
            if light.kind == "spot":
                factor = factor * spot_factor(-(unit @ light.toward), *light.spot)
        total += factor[..., None] * light.diffuse
    return total


def _tangent(points: np.ndarray, depth: np.ndarray, axis: int) -> np.ndarray:
    """Along ``axis`` of the image, each pixel's step to the neighbour nearer in depth (NaN where neither is)."""
    step = np.diff(points, axis=axis)
    jump = np.abs(np.diff(depth, axis=axis))
    jump[~np.isfinite(jump)] = np.inf
    pad = [(0, 0)] * depth.ndim
    after, before = list(pad), list(pad)
    after[axis], before[axis] = (0, 1), (1, 0)
    forward = np.pad(step, after + [(0, 0)], constant_values=np.nan)
    backward = np.pad(step, before + [(0, 0)], constant_values=np.nan)
    use_forward = np.pad(jump, after, constant_values=np.inf) <= np.pad(jump, before, constant_values=np.inf)
    return np.where(use_forward[..., None], forward, backward)


def surface(depth: np.ndarray, lens: Tuple[np.ndarray, np.ndarray]) -> Tuple[np.ndarray, np.ndarray]:
    """Points (H, W, 3) and unit normals facing the camera (zero where unknown), optical frame, of the surfaces
    the depth image (optical z; inf or NaN: nothing) shows; ``lens``: x / z of each column, y / z of each row."""
    columns, rows = lens
    depth = np.where(np.isfinite(depth), depth, np.nan)
    points = np.empty(depth.shape + (3,))
    points[:, :, 0] = columns[None, :] * depth
    points[:, :, 1] = rows[:, None] * depth
    points[:, :, 2] = depth
    with np.errstate(invalid="ignore"):
        normals = np.cross(_tangent(points, depth, 1), _tangent(points, depth, 0))
        length = np.sqrt(np.einsum("...i,...i->...", normals, normals))
        facing = np.where(np.einsum("...i,...i->...", normals, points) > 0.0, -1.0, 1.0)
        normals *= (facing / length)[..., None]
    normals[~np.isfinite(normals).all(axis=-1)] = 0.0
    return points, normals


def relight(
    rgb: np.ndarray,
    depth: np.ndarray,
    lens: Tuple[np.ndarray, np.ndarray],
    pose: Tuple[np.ndarray, np.ndarray],
    sun: np.ndarray,
    ambient: float,
    lights: List[PixelLight],
) -> np.ndarray:
    """``rgb`` (H, W, 3) uint8 as the ray casters shaded it (``ambient`` share, unit ``sun`` toward the light or
    zeros) with ``lights`` added; ``pose``: the optical frame's origin and rotation (world from optical)."""
    if not lights:
        return rgb
    origin, rotation = pose
    points, normals = surface(depth, lens)
    world_points = points @ rotation.T + origin
    world_normals = normals @ rotation.T
    sun_term = np.clip(world_normals @ sun, 0.0, 1.0)
    others = light_terms(np.nan_to_num(world_points), world_normals, lights)
    shade_all = ambient + (1.0 - ambient) * np.minimum(sun_term[..., None] + others, 1.0)
    scale = shade_all / (ambient + (1.0 - ambient) * sun_term)[..., None]
    return np.minimum(np.floor(rgb * scale + 0.5), 255.0).astype(np.uint8)
