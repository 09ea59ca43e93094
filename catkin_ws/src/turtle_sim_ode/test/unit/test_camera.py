"""Cameras without ROS: configuration read from model text, colours, and CPU rendering of depth and colour."""
from __future__ import annotations

import math
import os

import numpy as np
import ode
import pytest
from conftest import PACKAGE_ROOT, fixture_paths

from turtle_sim_ode.models.transforms import quat_from_rpy
from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.physics.trimesh import MeshGeom
from turtle_sim_ode.sensors import ray_kernel
from turtle_sim_ode.sensors.camera import CameraSensor
from turtle_sim_ode.sensors.config import read_sdf_sensors, read_sensors
from turtle_sim_ode.sensors.raycast import hit_capsule, hit_cylinder, hit_sphere
from turtle_sim_ode.world.simulation import Simulation

MODELS = PACKAGE_ROOT / "test" / "models"
WAFFLE = (MODELS / "waffle_depth_camera.urdf").read_text()
KINECT = (MODELS / "kinect_camera.urdf").read_text()
CAMERA_URDF = """<robot name="cam"><link name="base"><inertial><mass value="1"/>
<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
<gazebo reference="base"><sensor type="{kind}" name="cam"><update_rate>15</update_rate><pose>0 0 {z} 0 0 0</pose>
<camera><horizontal_fov>{fov}</horizontal_fov><image><width>{width}</width><height>{height}</height></image>
<clip><near>0.05</near><far>10</far></clip></camera>
<plugin name="c" filename="{plugin}"><cameraName>cam</cameraName><frameName>cam_optical</frameName></plugin>
</sensor></gazebo></robot>"""
RED_BOX = """<sdf version="1.6"><model name="red_box"><static>true</static><link name="link">
<collision name="c"><geometry><box><size>0.5 1 1</size></box></geometry></collision>
<visual name="v"><geometry><box><size>0.5 1 1</size></box></geometry>
<material><ambient>1 0 0 1</ambient><diffuse>1 0 0 1</diffuse></material></visual></link></model></sdf>"""
FACE_X = 1.5  # the box's near face, m in front of the camera


def camera_world(
    kind: str = "depth",
    plugin: str = "libgazebo_ros_openni_kinect.so",
    fov: float = 1.047,
    width: int = 320,
    height: int = 240,
    lens_z: float = 0.5,
    cube_z: float = 0.05,
) -> "tuple[Simulation, CameraSensor]":
    """A camera lens_z above a 0.1 m cube at the origin (centre cube_z high), looking along +x at a red box whose near face is
    FACE_X away."""
    sim = Simulation()
    urdf = CAMERA_URDF.format(kind=kind, plugin=plugin, fov=fov, width=width, height=height, z=lens_z)
    sim.spawn_urdf("cam", urdf, (0, 0, cube_z, 0, 0, 0))
    sim.spawn_sdf("red_box", RED_BOX, (FACE_X + 0.25, 0, 0.55, 0, 0, 0))
    return sim, CameraSensor(sim.physics, sim.models["cam"], sim.plugins["cam"].cameras[0])


def red_dominant(pixel: np.ndarray) -> bool:
    r, g, b = (int(v) for v in pixel)
    return r > 2 * max(g, b, 10)


def test_a_red_box_ahead_reads_red_and_at_its_distance_in_depth_and_cloud() -> None:
    sim, camera = camera_world()
    frame = camera.render(sim.scene)
    height, width = frame.depth.shape
    centre = (height // 2, width // 2)
    assert red_dominant(frame.rgb[centre])
    assert not red_dominant(frame.rgb[0, width // 2])  # sky above the box
    assert not red_dominant(frame.rgb[height - 1, width // 2])  # ground below it
    # The optical frame sits at the lens; the face is perpendicular to the optical axis, FACE_X away.
    origin, rotation = camera.optical_pose()
    assert origin == pytest.approx((0.0, 0.0, 0.55), abs=1e-6)
    assert frame.depth[centre] == pytest.approx(FACE_X, abs=0.01)
    point = camera.points(frame)[centre]
    world = origin + rotation @ point.astype(float)
    assert world[0] == pytest.approx(FACE_X, abs=0.01)
    assert abs(world[1]) <= 0.5 and abs(world[2] - 0.55) <= 0.5  # on the face
    # Sky: no depth (NaN as gazebo_ros has it); ground in front of the box: a depth, within the cutoffs.
    assert math.isnan(frame.depth[0, width // 2])
    assert np.isnan(camera.points(frame)[0, width // 2]).all()
    ground = camera.depth_image(frame)[height - 1, width // 2]
    assert 0.4 < ground < FACE_X


def test_the_focal_length_follows_fov_and_width_and_the_cloud_projects_back() -> None:
    sim, camera = camera_world(fov=1.2, width=200, height=100)
    assert camera.focal_length == pytest.approx(200 / (2 * math.tan(0.6)))
    frame = camera.render(sim.scene)
    cloud = camera.points(frame)
    for row, column in ((50, 100), (40, 120), (60, 70)):
        x, y, z = cloud[row, column]
        assert x / z * camera.focal_length + camera.cx == pytest.approx(column, abs=1e-3)
        assert y / z * camera.focal_length + camera.cy == pytest.approx(row, abs=1e-3)


def test_the_box_edge_falls_where_the_pinhole_puts_it() -> None:
    """The box's left edge (y = +0.5 m at x = 1.5 m) lies at column cx - f * 0.5 / 1.5."""
    sim, camera = camera_world(width=321, height=241)
    frame = camera.render(sim.scene)
    row = frame.rgb[120]
    red = [column for column in range(321) if red_dominant(row[column])]
    edge = camera.cx - camera.focal_length * 0.5 / FACE_X
    assert min(red) == pytest.approx(edge, abs=1.0)
    assert max(red) == pytest.approx(2 * camera.cx - edge, abs=1.0)


def test_a_camera_inside_its_own_model_sees_past_it() -> None:
    sim, camera = camera_world(lens_z=0.0, cube_z=0.55)  # the lens at the cube's centre
    frame = camera.render(sim.scene)
    assert frame.depth[120, 160] == pytest.approx(FACE_X, abs=0.01)


def test_primitives_are_hit_at_their_surfaces() -> None:
    origin = np.array([-3.0, 0.0, 0.0])
    ahead = np.array([[1.0, 0.0, 0.0]])
    assert hit_sphere(origin, ahead, 0.5, 0.0)[0][0] == pytest.approx(2.5)
    assert hit_cylinder(origin, ahead, 0.5, 2.0, 0.0)[0][0] == pytest.approx(2.5)
    down = np.array([[0.0, 0.0, -1.0]])
    assert hit_cylinder(np.array([0.0, 0.0, 3.0]), down, 0.5, 2.0, 0.0)[0][0] == pytest.approx(2.0)
    assert hit_capsule(np.array([0.0, 0.0, 3.0]), down, 0.5, 2.0, 0.0)[0][0] == pytest.approx(1.5)
    assert math.isinf(hit_sphere(origin, -ahead, 0.5, 0.0)[0][0])


def test_depth_and_camera_configs_take_gazebo_ros_defaults_and_the_models_tags() -> None:
    waffle = read_sensors(WAFFLE).cameras[0]
    assert (waffle.link, waffle.depth, waffle.width, waffle.height) == ("camera_rgb_frame", True, 160, 120)
    assert waffle.horizontal_fov == pytest.approx(1.3439)
    assert (waffle.camera_name, waffle.image_topic, waffle.points_topic) == ("camera", "rgb/image_raw", "depth/points")
    assert (waffle.frame, waffle.cutoff, waffle.cutoff_max) == ("camera_rgb_optical_frame", 0.4, 5.0)
    assert waffle.update_rate == 15.0  # the plugin's updateRate; the sensor has none
    kinect = read_sensors(KINECT).cameras[0]
    assert (kinect.update_rate, kinect.encoding, kinect.cutoff) == (10.0, "bgr8", 0.5)  # the slower of the two rates
    bare = read_sensors(
        CAMERA_URDF.format(kind="depth", plugin="libgazebo_ros_depth_camera.so", fov=1, width=8, height=6, z=0)
    ).cameras[0]
    assert (bare.image_topic, bare.info_topic) == ("ir/image_raw", "ir/camera_info")
    assert (bare.depth_topic, bare.depth_info_topic, bare.points_topic) == (
        "depth/image_raw",
        "depth/camera_info",
        "points",
    )
    plain = read_sensors(
        CAMERA_URDF.format(kind="camera", plugin="libgazebo_ros_camera.so", fov=1, width=8, height=6, z=0)
    ).cameras[0]
    assert (plain.depth, plain.image_topic, plain.info_topic, plain.encoding) == (
        False,
        "image_raw",
        "camera_info",
        "rgb8",
    )


@pytest.mark.parametrize(
    "change, message",
    [
        ("<horizontal_fov>1.047</horizontal_fov>", "<horizontal_fov>4</horizontal_fov>"),
        ("<width>320</width>", "<width>0</width>"),
        ("<width>320</width><height>240</height>", "<width>8192</width><height>8192</height>"),
        ("<near>0.05</near>", "<near>20</near>"),
    ],
)
def test_bad_camera_values_are_refused_naming_the_tag(change: str, message: str) -> None:
    urdf = CAMERA_URDF.format(
        kind="depth", plugin="libgazebo_ros_openni_kinect.so", fov=1.047, width=320, height=240, z=0
    ).replace(change, message)
    with pytest.raises(ModelError, match="<sensor name='cam'>"):
        read_sensors(urdf)


def test_unsupported_sensors_are_named_in_the_spawn_warnings() -> None:
    sim = Simulation()
    warnings = sim.spawn_urdf("kinect", KINECT)
    assert any("front_sonar" in w and "sonar" in w and "not simulated" in w for w in warnings), warnings
    urdf = CAMERA_URDF.format(kind="camera", plugin="libgazebo_ros_multicamera.so", fov=1, width=8, height=6, z=0)
    urdf = urdf.replace("</gazebo>", '<sensor type="gps" name="gps0"/></gazebo>')
    warnings = sim.spawn_urdf("other", urdf)
    assert any("gps0" in w and "gps" in w for w in warnings), warnings
    assert any("libgazebo_ros_multicamera.so" in w and "not published" in w for w in warnings), warnings
    assert sim.plugins["kinect"].cameras and not sim.plugins["other"].cameras


def test_link_colours_come_from_urdf_materials_gazebo_materials_and_sdf() -> None:
    waffle = parse_urdf(WAFFLE)
    assert waffle.links["base_link"].color == pytest.approx((0.175, 0.175, 0.175))  # Gazebo/DarkGrey wins
    assert parse_urdf(KINECT).links["base_link"].color == (1.0, 1.0, 1.0)  # inline <color rgba>
    named = WAFFLE.replace("<material>Gazebo/DarkGrey</material>", "")
    assert parse_urdf(named).links["base_link"].color == pytest.approx((0.3, 0.3, 0.3))  # the named material
    assert parse_urdf(WAFFLE).links["camera_link"].color is None
    assert parse_sdf_model(RED_BOX).links["link"].color == (1.0, 0.0, 0.0)
    script = RED_BOX.replace(
        "<ambient>1 0 0 1</ambient><diffuse>1 0 0 1</diffuse>", "<script><name>Gazebo/Blue</name></script>"
    )
    assert parse_sdf_model(script).links["link"].color == (0.0, 0.0, 1.0)


def test_the_ray_kernel_is_built_and_used_by_default() -> None:
    _, camera = camera_world(width=8, height=6)
    assert camera.uses_ray_kernel, "libturtle_sim_ode_rays.so not found: run scripts/build.sh"


# Visuals for the agreement test: a box drawn 0.3 m from its collision, a sphere, a mesh (mm, scale 0.001), turned.
VISUALS = """<sdf version="1.6"><model name="visuals"><static>true</static>
<link name="boxed"><pose>1.1 0.35 0.35 0.3 0.2 0.5</pose>
<collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
<visual name="v"><pose>0 0.3 0 0 0 0.7</pose><geometry><box><size>0.25 0.15 0.3</size></box></geometry>
<material><script><name>Gazebo/Orange</name></script></material></visual></link>
<link name="ball"><pose>1.3 -0.35 0.75 0 0 0</pose>
<visual name="v"><geometry><sphere><radius>0.12</radius></sphere></geometry>
<material><diffuse>0.2 0.3 0.9 1</diffuse></material></visual></link>
<link name="plate"><pose>0.7 -0.1 0.7 0 -0.3 0.4</pose>
<collision name="c"><geometry><sphere><radius>0.05</radius></sphere></geometry></collision>
<visual name="v"><geometry><mesh><uri>package://tso_mesh_worlds/meshes/plate.stl</uri><scale>0.001 0.001 0.001</scale>
</mesh></geometry><material><script><name>Gazebo/Purple</name></script></material></visual></link>
</model></sdf>"""


def test_the_c_and_numpy_ray_casters_draw_the_same_image() -> None:
    """Every shape and a mesh, turned every way, near and far, half out of the picture, and visuals (a box beside its
    collision, a sphere, a mesh): C and numpy rays agree."""
    sim, camera = camera_world(width=96, height=72)
    sim.resources = fixture_paths()
    sim.spawn_sdf("visuals", VISUALS)
    space = sim.physics.space
    shapes = [
        ode.GeomBox(space, (0.3, 0.5, 0.2)),
        ode.GeomSphere(space, 0.25),
        ode.GeomCylinder(space, 0.2, 0.6),
        ode.GeomCapsule(space, 0.15, 0.5),
        ode.GeomBox(space, (0.2, 0.2, 2.0)),
        ode.GeomBox(space, (4.0, 0.1, 1.0)),  # a wall beside the camera, from behind it to well ahead
        # A tetrahedron with one face wound the other way (meshes are drawn from both sides).
        MeshGeom(
            space, [(0, 0, 0), (0.4, 0, 0), (0, 0.4, 0), (0, 0, 0.4)], [(0, 2, 1), (0, 1, 3), (0, 2, 3), (1, 2, 3)]
        ),
    ]
    rng = np.random.default_rng(15)
    places = ((1.0, 0.6), (0.8, -0.5), (1.2, -0.2), (0.9, 0.2), (0.5, 0.9), (0.0, -0.7), (0.7, 0.0))
    for geom, (x, y) in zip(shapes, places):
        geom.setPosition((x, y, rng.uniform(0.2, 0.8)))
        angles = rng.uniform(-np.pi, np.pi, 3) if geom is not shapes[5] else (0.0, 0.0, 0.3)
        w, qx, qy, qz = quat_from_rpy(*angles)
        geom.setQuaternion((w, qx, qy, qz))
    numpy_camera = CameraSensor(sim.physics, sim.models["cam"], camera.config, ray_kernel=False)
    fast, slow = camera.render(sim.scene), numpy_camera.render(sim.scene)
    assert not sim.scene.take_warnings()
    assert (np.isnan(fast.depth) == np.isnan(slow.depth)).all()
    hit = ~np.isnan(fast.depth)
    assert np.allclose(fast.depth[hit], slow.depth[hit], rtol=1e-5, atol=1e-6)
    assert np.abs(fast.rgb.astype(int) - slow.rgb.astype(int)).max() <= 1
    fast_depth, fast_cloud, fast_dense = camera.organised_cloud(fast)
    slow_depth, slow_cloud, slow_dense = numpy_camera.organised_cloud(fast)
    np.testing.assert_array_equal(fast_depth, slow_depth)  # NaN where NaN (numpy 1.17 has no equal_nan)
    assert fast_dense == slow_dense
    fast_xyz = fast_cloud.view(np.float32)[:, :, :3]
    np.testing.assert_array_equal(fast_xyz, slow_cloud.view(np.float32)[:, :, :3])
    assert np.array_equal(fast_cloud[:, :, 12:], slow_cloud[:, :, 12:])
    drawn = {tuple(pixel) for pixel in fast.rgb.reshape(-1, 3)}
    assert len(drawn) > 8  # shapes, faces and shading, not one flat colour
    table, meshes = sim.scene.drawables(sim.physics, sim.models["cam"])
    assert len(meshes) == 2 and len(table) == len(shapes) - 1 + 2 + 1  # the boxed link's collision is not drawn


def test_an_sdf_link_sensor_is_a_camera_in_the_link_frame() -> None:
    sdf = RED_BOX.replace(
        "</link>",
        """<sensor type="camera" name="front"><pose>0.3 0 0.1 0 0 0</pose><update_rate>5</update_rate>
        <camera><horizontal_fov>0.9</horizontal_fov><image><width>64</width><height>48</height>
        <format>L8</format></image></camera>
        <plugin name="p" filename="libgazebo_ros_camera.so"><cameraName>front_cam</cameraName></plugin>
        </sensor></link>""",
    )
    config = read_sdf_sensors(sdf).cameras[0]
    assert (config.link, config.pose[:3], config.update_rate, config.encoding) == (
        "link",
        (0.3, 0.0, 0.1),
        5.0,
        "mono8",
    )
    assert (config.camera_name, config.frame, config.depth) == ("front_cam", "", False)


def test_the_worlds_sun_and_sky_light_the_picture() -> None:
    world = parse_sdf_world(
        """<sdf version="1.6"><world name="w"><include><uri>model://ground_plane</uri></include>
        <light type="directional" name="sun"><direction>0 0 -1</direction></light>
        <scene><background>0 0 1 1</background></scene></world></sdf>"""
    )
    sim = Simulation()
    sim.load_world(world)
    assert (sim.light_direction, sim.sky_colour) == ((0.0, 0.0, -1.0), (0.0, 0.0, 1.0))
    urdf = CAMERA_URDF.format(kind="camera", plugin="libgazebo_ros_camera.so", fov=1.047, width=32, height=24, z=0.5)
    sim.spawn_urdf("cam", urdf, (0, 0, 0.05, 0, 0, 0))
    config = sim.plugins["cam"].cameras[0]
    for kernel in (True, False):
        camera = CameraSensor(
            sim.physics,
            sim.models["cam"],
            config,
            sun_direction=sim.light_direction,
            sky=sim.sky_colour,
            ray_kernel=kernel,
        )
        frame = camera.render(sim.scene)
        assert tuple(frame.rgb[0, 16]) == (0, 0, 255)  # the sky
        assert tuple(frame.rgb[23, 16]) == (179, 179, 179)  # Gazebo/Grey ground, the sun straight above: 0.7 lit fully


@pytest.mark.parametrize(
    "cpu_max, cfs_quota, cfs_period, expected",
    [
        ("max 100000\n", None, None, None),
        ("150000 100000\n", None, None, 1.5),
        (None, "-1\n", "100000\n", None),
        (None, "200000\n", "100000\n", 2.0),
        (None, None, None, None),
    ],
)
def test_the_cpu_quota_of_a_container_bounds_the_ray_threads(tmp_path, cpu_max, cfs_quota, cfs_period, expected):
    paths = []
    for name, text in (("cpu.max", cpu_max), ("quota", cfs_quota), ("period", cfs_period)):
        path = tmp_path / name
        if text is not None:
            path.write_text(text)
        paths.append(str(path))
    assert ray_kernel.cpu_quota(*paths) == expected
    assert 1 <= ray_kernel.usable_cpus() <= len(os.sched_getaffinity(0))
