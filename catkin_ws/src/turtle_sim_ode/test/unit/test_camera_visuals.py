"""Cameras draw the models' visuals, as Gazebo's do: visuals nearer than their collisions, visual-only models, links
of several colours, visual meshes read through the resource paths; a link without visuals, or whose visual mesh
cannot be read (one warning), from its collisions; never the camera's own model. And visuals as the parsers read
them from URDF and SDF.

Fixture: test/models/visual_bot.urdf (meshes from test/fixtures/tso_mesh_worlds, see make_meshes.py)."""
from __future__ import annotations

from typing import List

import numpy as np
import pytest
from conftest import PACKAGE_ROOT, fixture_paths
from test_camera import CAMERA_URDF, RED_BOX, red_dominant

from turtle_sim_ode.models.materials import GAZEBO_MATERIALS
from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.description import Box, Mesh, Pose, Sphere
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.sensors.camera import CameraSensor, Frame
from turtle_sim_ode.world.simulation import Simulation

VISUAL_BOT = (PACKAGE_ROOT / "test" / "models" / "visual_bot.urdf").read_text()
PLATE_URI = "package://tso_mesh_worlds/meshes/plate.stl"
PLATE_FRONT = 0.4  # m ahead of visual_bot's base_link: the plate mesh's near face (make_meshes.PLATE_MM)
BOT_X = 1.0  # where the tests put visual_bot, ahead of the camera
DEPTH_TOLERANCE = 0.01
# A crate whose red visual stands 0.2 m nearer the camera than its collision box (SDF <pose> in the link).
CRATE = """<sdf version="1.6"><model name="crate"><static>true</static><link name="link">
<collision name="c"><geometry><box><size>0.5 1 1</size></box></geometry></collision>
<visual name="v"><pose>-0.2 0 0 0 0 0</pose><geometry><box><size>0.5 1 1</size></box></geometry>
<material><script><name>Gazebo/Red</name></script></material></visual></link></model></sdf>"""
# Decoration without collisions, as Gazebo worlds place markers.
MARKER = """<sdf version="1.6"><model name="marker"><static>true</static><link name="link">
<visual name="ball"><geometry><sphere><radius>0.3</radius></sphere></geometry>
<material><diffuse>0 1 0 1</diffuse></material></visual></link></model></sdf>"""
KERNELS = pytest.mark.parametrize("kernel", [True, False], ids=["c_rays", "numpy_rays"])


def camera_sim(lens_z: float = 0.5, camera_urdf: str = "") -> Simulation:
    """A 65 x 49 depth camera (the centre pixel looks straight ahead) at x = 0, lens_z + 0.05 high, on model 'cam'."""
    sim = Simulation()
    sim.resources = fixture_paths()
    urdf = camera_urdf or CAMERA_URDF.format(
        kind="depth", plugin="libgazebo_ros_openni_kinect.so", fov=1.047, width=65, height=49, z=lens_z
    )
    sim.spawn_urdf("cam", urdf, (0, 0, 0.05, 0, 0, 0))
    return sim


def render(sim: Simulation, kernel: bool) -> Frame:
    camera = CameraSensor(sim.physics, sim.models["cam"], sim.plugins["cam"].cameras[0], ray_kernel=kernel)
    return camera.render(sim.scene)


def centre_depth(frame: Frame) -> float:
    return float(frame.depth[24, 32])


@KERNELS
def test_the_camera_reads_the_visual_face_not_the_collision_behind_it(kernel: bool) -> None:
    sim = camera_sim()
    sim.spawn_sdf("crate", CRATE, (1.75, 0, 0.55, 0, 0, 0))  # collision face 1.5 m ahead, visual face 1.3 m
    frame = render(sim, kernel)
    assert centre_depth(frame) == pytest.approx(1.3, abs=DEPTH_TOLERANCE)
    assert red_dominant(frame.rgb[24, 32])


@KERNELS
def test_a_model_without_collisions_is_seen(kernel: bool) -> None:
    sim = camera_sim()
    sim.spawn_sdf("marker", MARKER, (1.5, 0, 0.55, 0, 0, 0))
    assert sim.models["marker"].geoms == {"link": []}
    frame = render(sim, kernel)
    assert centre_depth(frame) == pytest.approx(1.2, abs=DEPTH_TOLERANCE)
    r, g, b = (int(v) for v in frame.rgb[24, 32])
    assert g > 2 * max(r, b, 10)


@KERNELS
def test_a_link_with_two_visuals_shows_both_colours(kernel: bool) -> None:
    """visual_bot's bumper: red on its left (the image's left), blue on its right."""
    sim = camera_sim(lens_z=0.11)
    sim.spawn_urdf("bot", VISUAL_BOT, (BOT_X, 0, 0, 0, 0, 0))
    rgb = render(sim, kernel).rgb.astype(int)
    red = (rgb[:, :, 0] > 2 * np.maximum(rgb[:, :, 1:].max(axis=2), 10)).nonzero()
    blue = (rgb[:, :, 2] > 2 * np.maximum(rgb[:, :, :2].max(axis=2), 10)).nonzero()
    assert len(red[0]) > 4 and len(blue[0]) > 4
    # Columns: left of the centre, right of it; the centre column looks at the seam between the two.
    assert red[1].max() <= 32 <= blue[1].min() and red[1].min() < 28 and blue[1].max() > 36
    assert red[0].max() < 24 and blue[0].max() < 24  # rows: above the lens, as the bumper is


@KERNELS
def test_a_visual_mesh_is_seen_where_the_mesh_puts_it(kernel: bool) -> None:
    """The plate mesh (mm, scale 0.001) stands PLATE_FRONT ahead of base_link, its collision box 0.05 ahead."""
    sim = camera_sim(lens_z=0.11)  # the lens 0.16 m high: half way up the plate
    sim.spawn_urdf("bot", VISUAL_BOT, (BOT_X, 0, 0, 0, 0, 0))
    frame = render(sim, kernel)
    assert centre_depth(frame) == pytest.approx(BOT_X + PLATE_FRONT, abs=DEPTH_TOLERANCE)
    grey = round(GAZEBO_MATERIALS["Gazebo/DarkGrey"][0] * 255)  # the base's Gazebo material, lit by the sun
    assert abs(int(frame.rgb[24, 32, 0]) - grey) < grey
    assert not sim.scene.take_warnings()


def test_a_visual_mesh_that_cannot_be_read_warns_once_and_its_link_is_drawn_from_collisions() -> None:
    sim = camera_sim(lens_z=0.11)
    sim.spawn_urdf("bot", VISUAL_BOT.replace("meshes/plate.stl", "meshes/missing_plate.stl"), (BOT_X, 0, 0, 0, 0, 0))
    warnings: List[str] = []
    for kernel in (True, False, True):
        frame = render(sim, kernel)
        # The collision box's face, 0.05 m ahead of base_link.
        assert centre_depth(frame) == pytest.approx(BOT_X - 0.05, abs=DEPTH_TOLERANCE)
        warnings += sim.scene.take_warnings()
    assert len(warnings) == 1 and "missing_plate.stl" in warnings[0] and "base_link" in warnings[0], warnings


@KERNELS
def test_the_cameras_own_visuals_are_never_in_its_picture(kernel: bool) -> None:
    """A visual wall in front of the lens, on the camera's own model: the red box behind it is seen."""
    urdf = CAMERA_URDF.format(
        kind="depth", plugin="libgazebo_ros_openni_kinect.so", fov=1.047, width=65, height=49, z=0.5
    ).replace(
        "</collision></link>",
        '</collision><visual><origin xyz="0.3 0 0.5"/><geometry><box size="0.1 2 2"/>' "</geometry></visual></link>",
    )
    sim = camera_sim(camera_urdf=urdf)
    assert sim.models["cam"].robot.links["base"].visuals
    sim.spawn_sdf("red_box", RED_BOX, (1.75, 0, 0.55, 0, 0, 0))
    assert centre_depth(render(sim, kernel)) == pytest.approx(1.5, abs=DEPTH_TOLERANCE)


def test_a_deleted_model_leaves_nothing_behind_and_a_respawned_one_is_drawn_anew() -> None:
    sim = camera_sim()
    sim.spawn_sdf("thing", CRATE, (1.75, 0, 0.55, 0, 0, 0))
    assert centre_depth(render(sim, True)) == pytest.approx(1.3, abs=DEPTH_TOLERANCE)
    sim.delete("thing")
    assert np.isnan(centre_depth(render(sim, True)))
    sim.spawn_sdf("thing", MARKER, (1.5, 0, 0.55, 0, 0, 0))
    assert centre_depth(render(sim, True)) == pytest.approx(1.2, abs=DEPTH_TOLERANCE)


def test_a_simulation_without_cameras_reads_no_visual_mesh(monkeypatch) -> None:
    sim = Simulation()
    sim.resources = fixture_paths()
    read = []
    monkeypatch.setattr(type(sim.resources), "read", lambda self, *args, **kwargs: read.append(args))
    sim.spawn_urdf("bot", VISUAL_BOT, (BOT_X, 0, 0, 0, 0, 0))
    for _ in range(10):
        sim.step()
    assert read == []


def test_urdf_visuals_keep_their_origins_geometry_and_colours() -> None:
    robot = parse_urdf(VISUAL_BOT)
    (plate,) = robot.links["base_link"].visuals
    assert plate.geometry == Mesh(PLATE_URI, (0.001, 0.001, 0.001))
    assert plate.color == GAZEBO_MATERIALS["Gazebo/DarkGrey"]  # <gazebo reference><material> over light_black
    left, right = robot.links["bumper_link"].visuals
    assert (left.name, left.origin, left.geometry, left.color) == (
        "bumper_left",
        Pose((0.0, 0.1, 0.0)),
        Box((0.05, 0.2, 0.1)),
        (1.0, 0.0, 0.0),
    )
    assert (right.origin.xyz, right.color) == ((0.0, -0.1, 0.0), (0.0, 0.0, 1.0))  # the named material
    assert robot.links["bumper_link"].collisions == [] and robot.links["base_footprint"].visuals == []
    assert robot.links["bumper_link"].color == (1.0, 0.0, 0.0)  # the first visual colour
    unnamed = parse_urdf(VISUAL_BOT.replace('<material name="blue"/>', ""))
    assert unnamed.links["bumper_link"].visuals[1].color is None


def test_sdf_visuals_keep_poses_colours_and_nested_models_place_them() -> None:
    sdf = """<sdf version="1.4"><model name="outer"><link name="base">
    <inertial><mass>1</mass></inertial>
    <visual name="lamp"><pose>0 0 0.3 0 0 1.5708</pose><geometry><sphere><radius>0.05</radius></sphere></geometry>
    <material><ambient>0 0 1 1</ambient></material></visual>
    <visual name="floor"><geometry><plane><normal>0 0 1</normal><size>1 1</size></plane></geometry></visual>
    <visual name="outline"><geometry><polyline><point>0 0</point><height>1</height></polyline></geometry></visual>
    </link>
    <model name="inner"><pose>1 0 0 0 0 0</pose><link name="shell"><pose>0 2 0 0 0 0</pose>
    <inertial><mass>1</mass></inertial>
    <visual name="v"><pose>0.1 0 0 0 0 0</pose><geometry><box><size>1 2 3</size></box></geometry>
    <material><script><name>Gazebo/Red</name></script></material></visual></link></model>
    <joint name="j" type="fixed"><parent>base</parent><child>inner::shell</child></joint>
    </model></sdf>"""
    model = parse_sdf_model(sdf)
    lamp, floor = model.links["base"].visuals
    assert (lamp.geometry, lamp.color, lamp.origin.xyz) == (Sphere(0.05), (0.0, 0.0, 1.0), (0.0, 0.0, 0.3))
    assert lamp.origin.rpy[2] == pytest.approx(1.5708)
    assert isinstance(floor.geometry, Box) and floor.color is None  # a plane is drawn as the thin box it collides as
    assert any("'outline'" in warning and "<polyline>" in warning for warning in model.warnings)
    (shell,) = model.links["inner::shell"].visuals
    assert (shell.origin.xyz, shell.geometry, shell.color) == ((0.1, 0.0, 0.0), Box((1.0, 2.0, 3.0)), (1.0, 0.0, 0.0))
    assert model.joints["j"].origin.xyz == pytest.approx((1.0, 2.0, 0.0))  # the link moved, its visual with it


@pytest.mark.parametrize(
    "text, message",
    [
        (VISUAL_BOT.replace('<origin xyz="0 0.1 0"', '<origin xyz="0 nan 0"'), "link 'bumper_link' visual bumper_left"),
        (VISUAL_BOT.replace('<box size="0.05 0.2 0.1"/>', '<box size="0.05 -0.2 0.1"/>', 1), "visual bumper_left box"),
        (VISUAL_BOT.replace('scale="0.001 0.001 0.001"', 'scale="0 1 1"'), "link 'base_link' visual 0 mesh scale"),
        (CRATE.replace("<pose>-0.2 0 0 0 0 0</pose>", "<pose>-0.2 0 0 0 0</pose>"), "visual 'v' <pose>"),
        (
            CRATE.replace(
                "<size>0.5 1 1</size></box></geometry>\n<material>",
                "<size>0.5 1 1e9</size></box>" "</geometry>\n<material>",
            ),
            "visual 'v' <box> <size>",
        ),
    ],
)
def test_bad_numbers_in_a_visual_are_refused_naming_the_tag(text: str, message: str) -> None:
    with pytest.raises(ModelError, match=message):
        (parse_urdf if text.startswith("<?xml") else parse_sdf_model)(text)
