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
pixel's surface point comes from the depth (origin + depth along the pixel's ray), its normal from the inverse
depth's steps to its neighbours (on each image axis the smaller step, so a depth edge does not bend it; see
``surface``), and the pixel is scaled by shade_all / shade_sun, shade_all = AMBIENT + (1 - AMBIENT) min(1, sun term +
the other lights' terms) per channel (Ogre clamps the lights' sum to 1). No shadows: a light reaches every surface
facing it within its range."""
from __future__ import annotations

from dataclasses import dataclass, replace
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
    denominator = quadratic * distance
    denominator += linear
    denominator *= distance
    denominator += constant
    np.maximum(denominator, SMALLEST_DENOMINATOR, out=denominator)
    return np.where(distance <= range_, np.reciprocal(denominator, out=denominator), 0.0).astype(distance.dtype)


def spot_factor(rho: np.ndarray, cos_inner: float, cos_outer: float, falloff: float) -> np.ndarray:
    """Ogre's spot term of the cosine ``rho`` off the spot's axis: 1 inside the inner cone, 0 beyond the outer one,
    ((rho - cos_outer) / (cos_inner - cos_outer)) ^ falloff between (a cone without a rim where inner >= outer)."""
    width = cos_inner - cos_outer
    if width <= 0.0:
        return (rho > cos_outer).astype(rho.dtype)
    edge = np.clip((rho - cos_outer) / width, 0.0, 1.0)
    return np.where(edge > 0.0, edge ** max(falloff, 0.0), 0.0).astype(rho.dtype)


Components = Tuple[np.ndarray, np.ndarray, np.ndarray]  # x, y, z arrays of one shape (or broadcasting to it)


def _dot(a: Components, b: Components) -> np.ndarray:
    total = a[0] * b[0]
    total += a[1] * b[1]
    total += a[2] * b[2]
    return total


def light_terms(points: Components, normals: Components, lights: Sequence[PixelLight]) -> Components:
    """The lights' summed diffuse terms (red, green, blue arrays; unclamped) at ``points`` of unit ``normals``
    (zero: unlit), all in the lights' frame. Per light a few passes over scalar arrays (float32 where given)."""
    shape = np.broadcast(points[0], normals[0]).shape
    kind = np.result_type(points[0], normals[0])
    channels = [np.zeros(shape, dtype=kind) for _ in range(3)]
    for light in lights:
        if light.kind == "directional":
            factor = np.broadcast_to(_dot(normals, tuple(-light.toward.astype(kind))), shape)
        else:
            to_light = tuple(kind.type(p) - q for p, q in zip(light.position, points))
            distance = np.sqrt(_dot(to_light, to_light))
            inverse = np.reciprocal(np.maximum(distance, 1e-9))
            factor = _dot(normals, to_light)
            factor *= inverse
            factor *= attenuation(distance, *light.attenuation)
            if light.kind == "spot":
                rho = _dot(to_light, tuple(-light.toward.astype(kind)))
                rho *= inverse
                factor *= spot_factor(rho, *light.spot)
        factor = np.maximum(factor, 0.0)
        for channel, weight in zip(channels, light.diffuse):
            if weight > 0.0:
                channel += factor * kind.type(weight)
    return channels[0], channels[1], channels[2]


def _slope(w: np.ndarray, axis: int) -> np.ndarray:
    """Along ``axis`` of the image, each pixel's step in ``w`` to the neighbour whose step is smaller (the same
    surface, at a depth edge)."""
    step = np.diff(w, axis=axis)
    first, last = [slice(None)] * 2, [slice(None)] * 2
    first[axis], last[axis] = slice(1, None), slice(None, -1)
    forward, backward = step[tuple(first)], step[tuple(last)]
    slope = np.empty_like(w)
    inner, head, tail = [slice(None)] * 2, [slice(None)] * 2, [slice(None)] * 2
    inner[axis], head[axis], tail[axis] = slice(1, -1), slice(0, 1), slice(-1, None)
    slope[tuple(inner)] = np.where(np.abs(forward) <= np.abs(backward), forward, backward)
    slope[tuple(head)] = step[tuple(head)]
    slope[tuple(tail)] = step[tuple(tail)]
    return slope


def surface(depth: np.ndarray, lens: Tuple[np.ndarray, np.ndarray]) -> Tuple[Components, Components]:
    """Points and unit normals facing the camera (zero where nothing is hit), optical frame, float32 (H, W) arrays
    each, of the surfaces the depth image (optical z; inf or NaN: nothing) shows; ``lens``: x / z of each column, y / z
    of each row (evenly spaced, 1 / focal length apart). On a plane n . p = c the inverse depth w = 1 / z is
    (n . (u, v, 1)) / c, linear in u and v: its slopes and value give n / c = (w_u, w_v, w - u w_u - v w_v)."""
    columns, rows = lens
    u = columns.astype(np.float32)[None, :]
    v = rows.astype(np.float32)[:, None]
    z = depth.astype(np.float32)
    z[~np.isfinite(z)] = 0.0  # nothing hit: no point, no normal
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.reciprocal(z)
        w[z == 0.0] = 0.0
        focal = np.float32(1.0 / (columns[1] - columns[0])) if len(columns) > 1 else np.float32(1.0)
        w_u = _slope(w, 1) * focal if w.shape[1] > 1 else np.zeros_like(w)
        w_v = _slope(w, 0) * focal if w.shape[0] > 1 else np.zeros_like(w)
        w_1 = w - u * w_u
        w_1 -= v * w_v
        # (w_u, w_v, w_1) . p = w z = 1 for p = z (u, v, 1): the normal facing the camera is its opposite
        length = _dot((w_u, w_v, w_1), (w_u, w_v, w_1))
        length[w == 0.0] = np.inf
        scale = np.sqrt(length, out=length)
        np.reciprocal(scale, out=scale)
        scale *= -1.0
    return (u * z, v * z, z), (w_u * scale, w_v * scale, w_1 * scale)


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
    zeros) with ``lights`` added; ``pose``: the optical frame's origin and rotation (world from optical). The work
    is done in the optical frame (the lights moved into it)."""
    if not lights:
        return rgb
    origin, rotation = pose
    local = [
        replace(light, position=(light.position - origin) @ rotation, toward=light.toward @ rotation)
        for light in lights
    ]
    points, normals = surface(depth, lens)
    sun_term = np.clip(_dot(normals, tuple((np.asarray(sun, dtype=float) @ rotation).astype(np.float32))), 0.0, 1.0)
    lit = np.float32(1.0 - ambient)
    shade = np.stack([np.minimum(sun_term + term, 1.0) for term in light_terms(points, normals, local)], axis=-1)
    shade *= lit
    shade += np.float32(ambient)
    shade /= (np.float32(ambient) + lit * sun_term)[..., None]  # the ray caster's shade, in rgb already
    shade *= rgb
    shade += np.float32(0.5)
    return np.minimum(shade, 255.0, out=shade).astype(np.uint8)
