"""A camera on a model's link, rendered on the CPU by casting one ray per pixel (in C, see sensors.ray_kernel, or
with numpy, see sensors.raycast) into what sensors.scene draws of every other model (the links' visuals, or their
collisions where they have none) and the ground plane: a shaded colour image, a depth image (metres along the
optical axis, as Gazebo's depth cameras give it) and an organised point cloud in the optical frame.

The optical frame is gazebo_ros's: z along the sensor's x (forward), x to the image's right (the sensor's -y),
y down (the sensor's -z). A pixel (i, j) looks through its centre: x/z = (i - cx) / f, y/z = (j - cy) / f with
cx = (width - 1) / 2, cy = (height - 1) / 2, f = width / (2 tan(hfov / 2)).
"""
from __future__ import annotations

import random
from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

import numpy as np

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.lights import Light
from turtle_sim_ode.models.transforms import quat_matrix
from turtle_sim_ode.models.materials import GAZEBO_MATERIALS, RGB
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.sensors.plugins.camera import CameraConfig
from turtle_sim_ode.sensors.mounted import MountedSensor
from turtle_sim_ode.sensors.ray_kernel import RayCaster, primitive_row
from turtle_sim_ode.sensors.ray_kernel import library as ray_kernel_library
from turtle_sim_ode.sensors.raycast import Primitive, hit_plane, hit_triangle, mesh_triangles
from turtle_sim_ode.sensors.distortion import DistortionMap
from turtle_sim_ode.sensors.lighting import PixelLight, relight
from turtle_sim_ode.sensors.scene import Scene, TexturedRow
from turtle_sim_ode.sensors.texturing import apply_textures

# Gazebo's defaults: the scene's background, the ground_plane model's material, the sun model's direction.
SKY_COLOR: RGB = (0.7, 0.7, 0.7)
GROUND_COLOR: RGB = GAZEBO_MATERIALS["Gazebo/Grey"]
SUN_DIRECTION = (-0.5, 0.1, -0.9)
AMBIENT = 0.4  # share of a surface's colour lit from everywhere; the rest from the sun, by the cosine law
CLOUD_POINT_STEP = 32  # bytes a point: x, y, z, padding, rgb, padding (PointCloud2Modifier "xyz", "rgb")
# Optical frame from sensor frame (rows: optical x, y, z in sensor axes).
OPTICAL_FROM_SENSOR = np.array([[0.0, -1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]])


@dataclass
class Frame:
    """One rendering: ``rgb`` (H, W, 3) uint8; ``depth`` (H, W) float32 metres along the optical axis, NaN where
    nothing is within (near, far); ``pose``: the optical frame in the world (position, rotation matrix)."""

    rgb: np.ndarray
    depth: np.ndarray
    pose: Tuple[np.ndarray, np.ndarray]


class CameraSensor(MountedSensor):
    """Renders ``config``'s camera on ``link`` of ``model``: every model but its own (see sensors.scene), and the
    ground."""

    def __init__(
        self,
        physics: PhysicsWorld,
        model: BuiltModel,
        config: CameraConfig,
        rng: Optional[random.Random] = None,
        sun_direction: Optional[Tuple[float, float, float]] = None,
        ray_kernel: bool = True,
        sky: Optional[RGB] = None,
        threads: Optional[int] = None,
    ) -> None:
        """``sun_direction`` (the world's directional light) and ``sky`` default to Gazebo's; ``ray_kernel``: cast
        the rays in C (src/ray_camera.c) when the library is built, else with numpy; ``threads``: the C kernel's
        (default: every CPU the process may use)."""
        super().__init__(physics, model, config, rng)
        width, height = config.width, config.height
        self.focal_length = config.focal_length
        self.cx, self.cy = (width - 1) / 2.0, (height - 1) / 2.0
        u = (np.arange(width) - self.cx) / self.focal_length  # x / z of each column
        v = (np.arange(height) - self.cy) / self.focal_length  # y / z of each row
        self._u, self._v = u, v
        self._sky = sky if sky is not None else SKY_COLOR
        lens = config.lens
        self._distortion = None if lens.identity else DistortionMap.of(width, height, lens, config.border_crop)
        self.light_from(sun_direction)
        lib = ray_kernel_library() if ray_kernel else None
        self._caster = RayCaster(lib, width, height, threads) if lib is not None else None
        if self._caster is None:  # the numpy rays' directions (tens of MB for a full-HD camera: only if used)
            optical = np.empty((height, width, 3))
            optical[:, :, 0] = u[None, :]
            optical[:, :, 1] = v[:, None]
            optical[:, :, 2] = 1.0
            norm = np.linalg.norm(optical, axis=2)
            self._optical_dirs = optical / norm[:, :, None]  # unit ray directions, optical frame
            self._depth_per_distance = 1.0 / norm  # optical z of a hit per metre along its ray

    def light_from(self, sun_direction: Optional[Tuple[float, float, float]], lights: Sequence[Light] = ()) -> None:
        """Shade with this directional light from now on: None is Gazebo's default sun, (0, 0, 0) no sun (ambient
        light only); and add ``lights`` (point, spot, further directional ones) per pixel (sensors.lighting)."""
        light = -np.asarray(sun_direction if sun_direction is not None else SUN_DIRECTION, dtype=float)
        norm = np.linalg.norm(light)
        self._light = light / norm if norm > 0 else np.zeros(3)
        self._lights = [PixelLight.of(other) for other in lights]

    @property
    def uses_ray_kernel(self) -> bool:
        return self._caster is not None

    @property
    def frame(self) -> str:
        return self.config.frame or self.config.link

    def optical_pose(self) -> Tuple[np.ndarray, np.ndarray]:
        """The optical frame's origin and rotation (world from optical) now."""
        position, quaternion = self.world_transform()
        world_from_sensor = np.array(quat_matrix(quaternion))
        return np.array(position), world_from_sensor @ OPTICAL_FROM_SENSOR.T

    def _pixel_box(self, centre: np.ndarray, radius: float) -> Optional[Tuple[int, int, int, int]]:
        """Columns and rows (first, end) where a sphere at ``centre`` (optical frame) may show; None if nowhere."""
        x, y, z = centre
        config = self.config
        if z + radius < config.near or z - radius > config.far:
            return None
        if z - radius <= 1e-3:  # about the camera's plane: any pixel
            return 0, config.width, 0, config.height
        low, high = z - radius, z + radius
        f = self.focal_length
        columns = (
            f * min((x - radius) / low, (x - radius) / high) + self.cx,
            f * max((x + radius) / low, (x + radius) / high) + self.cx,
        )
        rows = (
            f * min((y - radius) / low, (y - radius) / high) + self.cy,
            f * max((y + radius) / low, (y + radius) / high) + self.cy,
        )
        i0, i1 = max(0, int(np.floor(columns[0]))), min(config.width, int(np.ceil(columns[1])) + 1)
        j0, j1 = max(0, int(np.floor(rows[0]))), min(config.height, int(np.ceil(rows[1])) + 1)
        if i0 >= i1 or j0 >= j1:
            return None
        return i0, i1, j0, j1

    def render(self, scene: Scene) -> Frame:
        """Cast every pixel's ray at what ``scene`` draws of the world (the camera's own model aside) and the ground."""
        config = self.config
        origin, rotation = self.optical_pose()
        textured: List[TexturedRow] = []
        table, meshes = scene.drawables(self.physics, self.model, textured)
        ground = self.physics.ground if self.physics.has_ground else None
        if self._caster is not None:
            # Near to far, the ground last: a farther surface then fails the depth test before it is shaded.
            near_first = table[np.argsort(((table[:, 1:4] - origin) ** 2).sum(axis=1), kind="stable")]
            depth64, depth, rgb = self._caster.render(
                near_first if ground is None else np.vstack((near_first, primitive_row(ground, GROUND_COLOR))),
                meshes,
                origin,
                rotation,
                config.near,
                config.far,
                (self.focal_length, self.cx, self.cy),
                self._light,
                AMBIENT,
                self._sky,
            )
            rgb = relight(rgb, depth64, (self._u, self._v), (origin, rotation), self._light, AMBIENT, self._lights)
            return Frame(self._finish(rgb, depth64, textured, origin, rotation), depth, (origin, rotation))
        height, width = config.height, config.width
        dirs = self._optical_dirs @ rotation.T  # world directions (H, W, 3)
        distance = np.full((height, width), np.inf)
        shade = np.empty((height, width, 3))
        shade[:, :] = self._sky
        t_min = config.near / self._depth_per_distance  # the near clip is a plane (depth), as in C and OpenGL

        def paint(t: np.ndarray, normals: np.ndarray, colour: RGB, box: Tuple[int, int, int, int]) -> None:
            i0, i1, j0, j1 = box
            region = distance[j0:j1, i0:i1]
            t = t.reshape(region.shape)
            nearer = t < region
            if not nearer.any():
                return
            region[nearer] = t[nearer]
            lit = np.clip(normals.reshape(region.shape + (3,))[nearer] @ self._light, 0.0, 1.0)
            shade[j0:j1, i0:i1][nearer] = np.outer(AMBIENT + (1.0 - AMBIENT) * lit, colour)

        if ground is not None:
            normal, offset = ground.getParams()
            t, normals = hit_plane(
                origin, dirs.reshape(-1, 3), np.array(normal, dtype=float), offset, t_min.reshape(-1)
            )
            paint(t, normals, GROUND_COLOR, (0, width, 0, height))
        for pose, vertices, faces in meshes:
            colour = tuple(pose[12:15])
            for corners in mesh_triangles(pose, vertices, faces):
                centre = corners.mean(axis=0)
                box = self._pixel_box(
                    (centre - origin) @ rotation, float(np.linalg.norm(corners - centre, axis=1).max())
                )
                if box is not None:
                    i0, i1, j0, j1 = box
                    t, normals = hit_triangle(
                        origin, dirs[j0:j1, i0:i1].reshape(-1, 3), corners, t_min[j0:j1, i0:i1].reshape(-1)
                    )
                    paint(t, normals, colour, box)
        for row in table:
            shape = Primitive(row)
            box = self._pixel_box((shape.position - origin) @ rotation, shape.radius)
            if box is not None:
                i0, i1, j0, j1 = box
                t, normals = shape.hit(origin, dirs[j0:j1, i0:i1].reshape(-1, 3), t_min[j0:j1, i0:i1].reshape(-1))
                paint(t, normals, shape.colour, box)
        depth = distance * self._depth_per_distance
        missed = ~(depth <= config.far)
        shade[missed] = self._sky
        depth[missed] = np.nan
        rgb = (np.clip(shade, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)
        rgb = relight(rgb, depth, (self._u, self._v), (origin, rotation), self._light, AMBIENT, self._lights)
        return Frame(self._finish(rgb, depth, textured, origin, rotation), depth.astype(np.float32), (origin, rotation))

    def _finish(
        self,
        rgb: np.ndarray,
        depth: np.ndarray,
        textured: List[TexturedRow],
        origin: np.ndarray,
        rotation: np.ndarray,
    ) -> np.ndarray:
        """The pinhole picture ``rgb`` (depth: optical z, float64) with its textures, lens distortion and noise."""
        config = self.config
        if textured:
            apply_textures(rgb, depth, textured, origin, rotation, (self._u, self._v), self._pixel_box)
        if self._distortion is not None:
            rgb = self._distortion.apply(rgb)
        if config.noise_stddev > 0 or config.noise_mean != 0:
            # One sample a pixel, added to each of its channels (0..1), as gazebo-classic's ImageGaussianNoiseModel
            # shader adds it; float32 (a 640 x 480 frame's noise in a few ms, not tens).
            noise = self._rng.standard_normal(rgb.shape[:2] + (1,), dtype=np.float32)
            noisy = rgb * np.float32(1.0 / 255.0) + (
                noise * np.float32(config.noise_stddev) + np.float32(config.noise_mean)
            )
            rgb = (np.clip(noisy, 0.0, 1.0) * np.float32(255.0) + np.float32(0.5)).astype(np.uint8)
        return rgb

    def depth_image(self, frame: Frame) -> np.ndarray:
        """The depth camera plugins' depth image: metres within (cutoff, cutoff_max), NaN elsewhere (float32)."""
        depth = frame.depth
        keep = (depth > self.config.cutoff) & (depth < self.config.cutoff_max)
        return np.where(keep, depth, np.float32(np.nan)).astype(np.float32)

    def organised_cloud(self, frame: Frame) -> Tuple[np.ndarray, np.ndarray, bool]:
        """The depth image (see depth_image), the organised cloud's bytes in gazebo_ros_openni_kinect's
        PointCloud2 layout ((H, W, CLOUD_POINT_STEP) uint8: x, y, z float32 at 0, 4, 8, NaN outside the cutoffs;
        b, g, r at 16, 17, 18 as PCL packs rgb) and whether every point is finite. With the ray kernel the arrays
        are overwritten by the next call."""
        config = self.config
        if self._caster is not None:
            lens = (self.focal_length, self.cx, self.cy)
            depth, cloud, missing = self._caster.cloud(frame.depth, frame.rgb, lens, config.cutoff, config.cutoff_max)
            return depth, cloud, missing == 0
        depth = self.depth_image(frame)
        height, width = depth.shape
        data = np.zeros((height, width, CLOUD_POINT_STEP // 4), dtype=np.float32)
        data[:, :, 0] = depth * self._u[None, :]
        data[:, :, 1] = depth * self._v[:, None]
        data[:, :, 2] = depth
        cloud = data.view(np.uint8).reshape(height, width, CLOUD_POINT_STEP)
        cloud[:, :, 16:19] = frame.rgb[:, :, ::-1]
        return depth, cloud, bool(np.isfinite(depth).all())

    def points(self, frame: Frame) -> np.ndarray:
        """The organised cloud, (H, W, 3) float32 x, y, z in the optical frame; NaN outside the cutoffs."""
        depth = self.depth_image(frame)
        cloud = np.empty(depth.shape + (3,), dtype=np.float32)
        cloud[:, :, 0] = depth * self._u[None, :]
        cloud[:, :, 1] = depth * self._v[:, None]
        cloud[:, :, 2] = depth
        return cloud
