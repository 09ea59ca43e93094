"""Lens distortion of a camera's picture, as gazebo-classic's rendering::Distortion applies it (gazebo/rendering/
Distortion.cc): Brown's model in texture coordinates (0..1 across the image, ``center`` the lens centre),
Distort(p) = c + n (1 + k1 r^2 + k2 r^4 + k3 r^6) + tangential(p1, p2), n = p - c, r = |n|. The pinhole picture
at ``p`` shows in the distorted picture at Distort(p); a distorted pixel whose source lies outside the picture is
black. Barrel distortion (k1 < 0) is cropped (Distortion::SetCamera) unless the camera plugin's <borderCrop> is false
(GazeboRosCameraUtils passes it to Distortion::SetCrop): the picture is scaled about the image centre by
Distort(1, 1) - Distort(0, 0) so that the distorted frame fills it, as the CameraDistortionMap shader's ``scale``
does.

Gazebo splats a forward map into a texture and fills its holes; here each distorted pixel's source is found by
inverting Distort (fixed-point iteration, as OpenCV's undistortPoints does), and the pinhole picture is sampled
bilinearly there. The map is computed once per camera; a frame costs four gathers (numpy)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Tuple

import numpy as np

# Fixed-point steps inverting Distort, until no point moves by more than CONVERGED: about 30 for the distortions of
# gazebo_plugins' tests (k 0.1), up to ~150 for the strongest a camera's <distortion> takes here (k1 0.2, k2 0.1,
# k3 0.05 at a corner), where 30 left corner pixels 4e-4 off, and black.
MAX_ITERATIONS = 300
CONVERGED = 1e-13  # texture units
SOURCE_TOLERANCE = 1e-6  # texture units: a source whose Distort misses its pixel by more is none (black)


@dataclass(frozen=True)
class LensDistortion:
    """SDF ``<camera><distortion>``: k1, k2, k3, p1, p2 and ``center`` (texture coordinates), defaults SDF's."""

    k1: float = 0.0
    k2: float = 0.0
    k3: float = 0.0
    p1: float = 0.0
    p2: float = 0.0
    center: Tuple[float, float] = (0.5, 0.5)

    @property
    def identity(self) -> bool:
        return not any((self.k1, self.k2, self.k3, self.p1, self.p2))

    @property
    def barrel(self) -> bool:
        """k1 < 0: Distortion::SetCamera crops the picture to hide the black border."""
        return self.k1 < 0

    def ros_coefficients(self) -> Tuple[float, float, float, float, float]:
        """camera_info's D (plumb_bob): k1, k2, p1, p2, k3 (GazeboRosCameraUtils::Init with <autoDistortion>)."""
        return (self.k1, self.k2, self.p1, self.p2, self.k3)


def distort(points: np.ndarray, lens: LensDistortion) -> np.ndarray:
    """Distortion::Distort of texture coordinates ``points`` (..., 2)."""
    n = points - np.asarray(lens.center)
    x, y = n[..., 0], n[..., 1]
    r2 = x * x + y * y
    radial = 1.0 + lens.k1 * r2 + lens.k2 * r2 * r2 + lens.k3 * r2 * r2 * r2
    out = np.empty_like(n)
    out[..., 0] = x * radial + lens.p2 * (r2 + 2.0 * x * x) + 2.0 * lens.p1 * x * y
    out[..., 1] = y * radial + lens.p1 * (r2 + 2.0 * y * y) + 2.0 * lens.p2 * x * y
    return out + np.asarray(lens.center)


def undistort(points: np.ndarray, lens: LensDistortion) -> Tuple[np.ndarray, np.ndarray]:
    """The texture coordinates whose Distort is ``points`` (..., 2), and where that holds to SOURCE_TOLERANCE."""
    centre = np.asarray(lens.center)
    target = points - centre
    n = target.copy()
    for _ in range(MAX_ITERATIONS):
        x, y = n[..., 0], n[..., 1]
        r2 = x * x + y * y
        radial = 1.0 + lens.k1 * r2 + lens.k2 * r2 * r2 + lens.k3 * r2 * r2 * r2
        dx = lens.p2 * (r2 + 2.0 * x * x) + 2.0 * lens.p1 * x * y
        dy = lens.p1 * (r2 + 2.0 * y * y) + 2.0 * lens.p2 * x * y
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            moved, n = n, np.stack(((target[..., 0] - dx) / radial, (target[..., 1] - dy) / radial), axis=-1)
            change = np.abs(n - moved)
        if not np.any(change[np.isfinite(change)] > CONVERGED):  # points that diverged are left to ``found``
            break
    source = n + centre
    with np.errstate(invalid="ignore", over="ignore"):
        found = np.all(np.abs(distort(source, lens) - points) <= SOURCE_TOLERANCE, axis=-1)
    return source, found


@dataclass
class DistortionMap:
    """For each pixel of a distorted (H, W) picture: the pinhole pixel pairs (p, p + 1) above and below its source
    point (flat indices of p) and the four bilinear weights in 1/256 (0 for a pixel without a source: black)."""

    above: np.ndarray  # (H * W,) intp
    below: np.ndarray
    weights: np.ndarray  # (4, H * W, 1) uint16: above-left, above-right, below-left, below-right; sum 256 or 0

    @classmethod
    def of(cls, width: int, height: int, lens: LensDistortion, border_crop: bool = True) -> "DistortionMap":
        """The map of a ``width`` x ``height`` camera (at least 2 x 2); ``border_crop``: the plugin's <borderCrop>."""
        columns, rows = np.meshgrid((np.arange(width) + 0.5) / width, (np.arange(height) + 0.5) / height)
        wanted = np.stack((columns, rows), axis=-1)  # texture coordinates of the distorted pixels' centres
        if lens.barrel and border_crop:
            scale = distort(np.array([1.0, 1.0]), lens) - distort(np.array([0.0, 0.0]), lens)
            wanted = 0.5 + (wanted - 0.5) * scale
        source, found = undistort(wanted, lens)
        x = source[..., 0] * width - 0.5  # pinhole pixel coordinates (centres at integers)
        y = source[..., 1] * height - 0.5
        with np.errstate(invalid="ignore"):
            found &= (x >= -0.5) & (x <= width - 0.5) & (y >= -0.5) & (y <= height - 0.5)
        x = np.clip(np.where(found, x, 0.0), 0.0, width - 1.0)
        y = np.clip(np.where(found, y, 0.0), 0.0, height - 1.0)
        x0 = np.minimum(np.floor(x), width - 2).astype(np.intp)
        y0 = np.minimum(np.floor(y), height - 2).astype(np.intp)
        fx, fy = (x - x0).reshape(-1), (y - y0).reshape(-1)
        weights = np.stack(((1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy))
        fixed = np.rint(weights * 256.0).astype(np.int64)
        largest = np.argmax(fixed, axis=0)
        fixed[largest, np.arange(fixed.shape[1])] += 256 - fixed.sum(axis=0)  # the four always sum to 256
        fixed *= found.reshape(-1)
        above = (y0 * width + x0).reshape(-1)
        return cls(above, above + width, fixed.reshape(4, -1, 1).astype(np.uint16))

    def apply(self, rgb: np.ndarray) -> np.ndarray:
        """The distorted picture of a pinhole picture ``rgb`` (H, W, 3) uint8: two gathers of pixel pairs and
        fixed-point blending (uint16)."""
        flat = np.ascontiguousarray(rgb).reshape(-1)
        # (N - 1, 6): pixel p and pixel p + 1 side by side, a view of the same bytes
        pairs = np.lib.stride_tricks.as_strided(flat, shape=(len(flat) // 3 - 1, 6), strides=(3, 1))
        above, below = pairs[self.above], pairs[self.below]
        weights = self.weights
        blended = above[:, :3] * weights[0]
        blended += above[:, 3:] * weights[1]
        blended += below[:, :3] * weights[2]
        blended += below[:, 3:] * weights[3]
        blended += 128
        return (blended >> 8).astype(np.uint8).reshape(rgb.shape)
