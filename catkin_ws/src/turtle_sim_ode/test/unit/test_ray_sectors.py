"""The multi-beam lidars' broad phase (src/ray_sectors.c, issue #33): with more rays than sectors of azimuth, each ray
tests only the shapes listed in its sector. The distances must be those of testing every shape (the same call in
batches too small to be sorted, bit for bit), for shapes anywhere around the origin, above it, across azimuth +-pi,
and for rays straight up or down."""
from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from workspace_testing.timing import assert_within, best_seconds

from turtle_sim_ode.sensors import ray_kernel
from turtle_sim_ode.sensors.ray_kernel import BOX, CAPSULE, CYLINDER, PLANE, SPHERE, cast_rays, mesh_pose, shape_row

UNSORTED_BATCH = 500  # fewer rays than the kernel's 512 sectors: every shape tested
IDENTITY = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
TETRAHEDRON = (
    np.array([[0.0, 0.0, 0.0], [0.4, 0.0, 0.0], [0.0, 0.4, 0.0], [0.0, 0.0, 0.4]]),
    np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]], dtype=np.uint32),
)


def rotation(yaw: float, pitch: float) -> tuple:
    cy, sy, cp, sp = math.cos(yaw), math.sin(yaw), math.cos(pitch), math.sin(pitch)
    return (cy * cp, -sy, cy * sp, sy * cp, cy, sy * sp, -sp, 0.0, cp)


def lidar_directions(columns: int, lasers: int) -> np.ndarray:
    """A VLP-16-like pattern (azimuth -pi .. pi inclusive, +-15 deg), plus straight up and straight down."""
    azimuth, elevation = np.meshgrid(np.linspace(-math.pi, math.pi, columns), np.linspace(-0.26, 0.26, lasers))
    rays = np.stack((np.cos(elevation) * np.cos(azimuth), np.cos(elevation) * np.sin(azimuth), np.sin(elevation)), -1)
    return np.concatenate((rays.reshape(-1, 3), [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]))


def sorted_and_every(origin, directions, table, meshes):
    """The distances of one call (sorted into sectors) and of calls in batches too small to be sorted."""
    lib = ray_kernel.library()
    assert lib is not None, "libturtle_sim_ode_rays.so not found: run scripts/build.sh"

    def cast(rays):
        return cast_rays(lib, origin, np.eye(3), rays, table, meshes, 0.05, 50.0, 1)[0]

    def every():
        return np.concatenate(
            [cast(directions[i : i + UNSORTED_BATCH]) for i in range(0, len(directions), UNSORTED_BATCH)]
        )

    return (lambda: cast(directions)), every


def test_a_room_of_shapes_gives_the_same_distances_in_less_time() -> None:
    rows = [
        shape_row(BOX, (0.1, 1.0, 1.0), (5.0 * math.cos(a), 5.0 * math.sin(a), 0.5), rotation(a, 0.0), (1, 1, 1))
        for a in np.linspace(-math.pi, math.pi, 12, endpoint=False)
    ]
    rows.append(shape_row(SPHERE, (0.3,), (-2.0, -0.001, 0.2), IDENTITY, (1, 1, 1)))  # across azimuth +-pi
    rows.append(shape_row(CYLINDER, (0.2, 2.0), (0.0, 0.0, -0.5), IDENTITY, (1, 1, 1)))  # under the origin
    plane = np.zeros(ray_kernel.STRIDE)
    plane[0], plane[4:7], plane[13] = PLANE, (0.0, 0.0, 1.0), -1.0
    rows.append(plane)
    meshes = [(mesh_pose((1.0, 1.0, 0.0), IDENTITY, (1, 1, 1)), *TETRAHEDRON)]
    sorted_, every = sorted_and_every(np.zeros(3), lidar_directions(1800, 16), np.array(rows), meshes)
    distances = sorted_()
    assert np.array_equal(distances, every())
    assert (distances < 50.0).mean() > 0.5  # 50: the range, read where nothing is hit
    # The point of the sectors: a VLP-16 scan of this room takes at most half the time (compared in this run).
    assert_within(best_seconds(sorted_, 5), best_seconds(every, 5), 0.5, "a scan sorted into sectors")


shape = st.tuples(
    st.sampled_from([BOX, SPHERE, CYLINDER, CAPSULE]),
    st.tuples(*[st.floats(0.01, 2.0)] * 3),
    st.tuples(*[st.floats(-6.0, 6.0)] * 3),
    st.floats(-math.pi, math.pi),
    st.floats(-math.pi, math.pi),
)


@settings(max_examples=40, deadline=None)
@given(
    shapes=st.lists(shape, min_size=1, max_size=12),
    origin=st.tuples(*[st.floats(-3.0, 3.0)] * 3),
    mesh_at=st.tuples(*[st.floats(-4.0, 4.0)] * 3),
)
def test_generated_scenes_give_the_same_distances(shapes, origin, mesh_at) -> None:
    rows = []
    for kind, sizes, position, yaw, pitch in shapes:
        count = {BOX: 3, SPHERE: 1}.get(kind, 2)
        rows.append(shape_row(kind, sizes[:count], position, rotation(yaw, pitch), (1, 1, 1)))
    meshes = [(mesh_pose(mesh_at, rotation(0.3, 0.2), (1, 1, 1)), *TETRAHEDRON)]
    sorted_, every = sorted_and_every(np.array(origin), lidar_directions(90, 8), np.array(rows), meshes)
    assert np.array_equal(sorted_(), every())
