"""A multi-beam ray sensor, Gazebo's RaySensor with vertical samples (a Velodyne's): a grid of unit rays from the
sensor's pose, cast at the collision geoms of every model but its own and at the ground, in C
(sensors.ray_kernel's tso_rays) or, where the library is not built, with numpy (sensors.raycast)."""
from __future__ import annotations

import math
import random
from typing import List, NamedTuple, Optional, Tuple

import numpy as np

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.models.transforms import quat_matrix
from turtle_sim_ode.physics.trimesh import MeshGeom
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.sensors.mounted import MountedSensor
from turtle_sim_ode.sensors.ray_kernel import PLANE, MeshItem, cast_rays, mesh_pose, primitive_row, usable_cpus
from turtle_sim_ode.sensors.ray_kernel import library as ray_kernel_library
from turtle_sim_ode.sensors.raycast import Primitive, hit_plane, hit_triangle, mesh_triangles
from turtle_sim_ode.sensors.rays import world_geoms
from turtle_sim_ode.sensors.sensor_element import RayGridConfig

NO_COLOUR = (0.0, 0.0, 0.0)


def grid_angles(count: int, low: float, high: float) -> np.ndarray:
    """Gazebo's MultiRayShape angles: ``count`` from ``low`` to ``high`` inclusive (``low`` alone for one ray)."""
    return low + np.arange(count) * ((high - low) / (count - 1)) if count > 1 else np.array([low])


class ScanGeometry(NamedTuple):
    """What a scan's rays are cast at, taken from the world at one sim time: the sensor's origin and rotation (world
    from sensor), the primitive rows and the meshes within reach (sensors.ray_kernel's table and MeshItem)."""

    origin: np.ndarray
    rotation: np.ndarray
    table: np.ndarray
    meshes: List[MeshItem]


class MultiBeamLidar(MountedSensor):
    """``ranges()``: (vertical_samples, samples) distances (m) along rays at yaw y_i and pitch p_j in the sensor
    frame, direction (cos p cos y, cos p sin y, sin p) as Gazebo's MultiRayShape has it; a ray sees what lies
    between range_min and range_max, and reads range_max where it hits nothing (as Gazebo's RaySensor)."""

    def __init__(
        self,
        physics: PhysicsWorld,
        model: BuiltModel,
        config: RayGridConfig,
        rng: Optional[random.Random] = None,
        ray_kernel: bool = True,
        threads: Optional[int] = None,
    ) -> None:
        super().__init__(physics, model, config, rng)
        self.yaws = grid_angles(config.samples, config.min_angle, config.max_angle)
        self.pitches = grid_angles(config.vertical_samples, config.vertical_min_angle, config.vertical_max_angle)
        pitch, yaw = np.meshgrid(self.pitches, self.yaws, indexing="ij")
        self._local = np.stack((np.cos(pitch) * np.cos(yaw), np.cos(pitch) * np.sin(yaw), np.sin(pitch)), axis=-1)
        self._lib = ray_kernel_library() if ray_kernel else None
        self._threads = threads if threads is not None else usable_cpus()
        self.tests = 0  # ray tests made by the last scan (C kernel)

    @property
    def directions(self) -> np.ndarray:
        """The rays' unit vectors in the sensor frame, (vertical_samples, samples, 3)."""
        return self._local

    @property
    def uses_ray_kernel(self) -> bool:
        return self._lib is not None

    def pose(self) -> Tuple[np.ndarray, np.ndarray]:
        """The sensor's origin and rotation (world from sensor) now."""
        position, quaternion = self.world_transform()
        return np.array(position), np.array(quat_matrix(quaternion))

    def _shapes(self, origin: np.ndarray) -> Tuple[np.ndarray, List[MeshItem]]:
        """The primitive rows and meshes within reach (the ground last)."""
        reach = self.config.range_max

        def in_reach(space) -> bool:  # type: ignore[no-untyped-def]
            x0, x1, y0, y1, z0, z1 = space.getAABB()
            nearest = np.clip(origin, (x0, y0, z0), (x1, y1, z1))
            return float(((nearest - origin) ** 2).sum()) <= reach * reach

        rows, meshes = [], []
        for geom in world_geoms(self.physics, self.model, in_reach):
            if isinstance(geom, MeshGeom):
                meshes.append((mesh_pose(geom.getPosition(), geom.getRotation(), NO_COLOUR), geom.vertices, geom.faces))
                continue
            row = primitive_row(geom, NO_COLOUR)
            if row is not None:
                rows.append(row)
        if self.physics.has_ground:
            rows.append(primitive_row(self.physics.ground, NO_COLOUR))
        return np.array(rows), meshes

    def geometry(self) -> ScanGeometry:
        """The scan's geometry now, copied out of the world (the thread that steps it must take it)."""
        origin, rotation = self.pose()
        return ScanGeometry(origin, rotation, *self._shapes(origin))

    def cast(self, geometry: ScanGeometry, noisy: bool = True) -> np.ndarray:
        """The scan of ``geometry``; it reads nothing of the world, so any one thread at a time may cast.
        ``noisy``: with the sensor's ``<ray><noise>`` (Gazebo's RaySensor adds it to the ranges of its scan message;
        its ray shape, which gazebo_ros_block_laser reads, stays without: pass False)."""
        config = self.config
        origin, rotation, table, meshes = geometry
        local = self._local.reshape(-1, 3)
        if self._lib is not None:
            distance, self.tests = cast_rays(
                self._lib, origin, rotation, local, table, meshes, config.range_min, config.range_max, self._threads
            )
        else:
            distance = self._numpy_rays(origin, local @ rotation.T, table, meshes)
            distance[~(distance <= config.range_max)] = config.range_max
        if noisy and (config.noise_stddev > 0 or config.noise_mean != 0):
            distance += self._rng.normal(config.noise_mean, config.noise_stddev, distance.shape)
        return distance.reshape(config.vertical_samples, config.samples)

    def ranges(self, noisy: bool = True) -> np.ndarray:
        """The scan of the world now (``noisy``: see cast)."""
        return self.cast(self.geometry(), noisy)

    def _numpy_rays(
        self, origin: np.ndarray, directions: np.ndarray, table: np.ndarray, meshes: List[MeshItem]
    ) -> np.ndarray:
        t_min = self.config.range_min
        best = np.full(len(directions), math.inf)
        for row in table:
            if int(row[0]) == PLANE:
                t, _ = hit_plane(origin, directions, row[4:7], float(row[13]), t_min)
            else:
                t, _ = Primitive(row).hit(origin, directions, t_min)
            np.minimum(best, t, out=best)
        for pose, vertices, faces in meshes:
            for corners in mesh_triangles(pose, vertices, faces):
                np.minimum(best, hit_triangle(origin, directions, corners, t_min)[0], out=best)
        return best
