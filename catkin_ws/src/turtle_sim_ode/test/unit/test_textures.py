"""Textures from materials, as Gazebo models name them: an SDF <material><script> whose <uri>s hold Ogre material
scripts and images (gazebo_models' checkerboard_plane, Gazebo's own media), the script's first texture_unit texture
(Ogre's material script format), drawn by the cameras on the textured surface, times its shading.

Fixture: gazebo_ros/test/models/checkerboard_plane (ours: a 2 m board of 8 x 8 squares, top at z = 0)."""
from __future__ import annotations

from pathlib import Path
from xml.etree.ElementTree import fromstring

import numpy as np
import pytest
from conftest import PACKAGE_ROOT
from hypothesis import given
from hypothesis import strategies as st

from turtle_sim_ode.models.resources import ResourcePaths
from turtle_sim_ode.models.sdf import parse_sdf_model
from turtle_sim_ode.models.text import ModelError
from turtle_sim_ode.models.textures import (
    MaterialScript,
    decode_image,
    read_texture,
    script_textures,
    sdf_material_script,
    texture_lookup,
)
from turtle_sim_ode.sensors.camera import CameraSensor
from turtle_sim_ode.sensors.scene import Scene
from turtle_sim_ode.sensors.texturing import face_uv
from turtle_sim_ode.world.simulation import Simulation

MODELS = PACKAGE_ROOT.parent / "gazebo_ros" / "test" / "models"
BOARD = MODELS / "checkerboard_plane"
SCRIPT = """// a comment: material Not/This
material Plain/Red
{
  technique { pass { diffuse 1 0 0 1 } }
}
material Board/Checks
{
  technique
  {
    pass
    {
      texture_unit
      {
        texture checks.png   // the image
        filtering none
      }
      texture_unit { texture second.png }
    }
  }
}
"""
# A camera looking straight down from 2.5 m at the board (what gazebo_plugins' distortion test worlds do).
DOWN_CAMERA = """<sdf version="1.6"><model name="cam"><static>true</static><link name="l"><pose>0 0 2.5 0 1.5707963 0</pose>
<sensor type="camera" name="c"><camera><horizontal_fov>0.927295218</horizontal_fov>
<image><width>80</width><height>80</height></image><clip><near>0.02</near><far>300</far></clip></camera>
<plugin name="p" filename="libgazebo_ros_camera.so"/></sensor></link></model></sdf>"""


def paths() -> ResourcePaths:
    return ResourcePaths({}, [str(MODELS)], [str(MODELS)])


def test_a_script_names_each_materials_first_texture() -> None:
    assert script_textures(SCRIPT) == {"Board/Checks": "checks.png"}


def test_sdf_scripts_with_folders_are_textures_and_gazebos_own_names_are_colours() -> None:
    visual = fromstring(
        "<visual><material><script><uri>model://m/materials/scripts</uri><uri>model://m/materials/textures</uri>"
        "<name>Board/Checks</name></script></material></visual>"
    )
    assert sdf_material_script(visual) == MaterialScript(
        ("model://m/materials/scripts", "model://m/materials/textures"), "Board/Checks"
    )
    gazebo = fromstring(
        "<visual><material><script><uri>file://media/materials/scripts/gazebo.material</uri>"
        "<name>Gazebo/Red</name></script></material></visual>"
    )
    assert sdf_material_script(gazebo) is None


def test_the_fixture_board_texture_is_read_through_the_model_path() -> None:
    model = parse_sdf_model((BOARD / "model.sdf").read_text())
    (visual,) = model.links["link"].visuals
    image = read_texture(paths(), visual.texture, str(BOARD))
    assert image.shape == (8, 8, 3)
    assert np.all(image[0, 0] == 0.0) and np.all(image[0, 1] == 1.0) and np.all(image[1, 1] == 0.0)


def test_a_missing_texture_or_material_is_named(tmp_path: Path) -> None:
    (tmp_path / "board.material").write_text(SCRIPT)
    folder = ResourcePaths({}, [], [str(tmp_path)])
    with pytest.raises(ModelError, match="texture 'checks.png'"):
        read_texture(folder, MaterialScript((str(tmp_path),), "Board/Checks"), None)
    with pytest.raises(ModelError, match="material 'No/Such'"):
        read_texture(folder, MaterialScript((str(tmp_path),), "No/Such"), None)
    with pytest.raises(ModelError, match="not an image"):
        decode_image(b"not a png", "x.png")


def test_texture_lookup_takes_the_nearest_texel_and_wraps() -> None:
    image = np.arange(12, dtype=np.float32).reshape(2, 2, 3)
    u = np.array([0.1, 0.9, 0.9, 1.1])
    v = np.array([0.1, 0.1, 0.6, 0.6])
    assert texture_lookup(image, u, v)[:, 0].tolist() == [0.0, 3.0, 9.0, 6.0]


@given(
    st.tuples(*(st.floats(0.01, 5.0) for _ in range(3))),
    st.integers(0, 5),
    st.floats(-1.0, 1.0),
    st.floats(-1.0, 1.0),
)
def test_every_point_on_a_box_face_has_texture_coordinates_in_0_1(half, face, a, b) -> None:  # type: ignore[no-untyped-def]
    half = np.array(half)
    axis, sign = face // 2, 1.0 if face % 2 == 0 else -1.0
    point = np.empty(3)
    others = [index for index in range(3) if index != axis]
    point[axis] = sign * half[axis]
    point[others[0]], point[others[1]] = a * half[others[0]], b * half[others[1]]
    u, v = face_uv(point[None, :], half)
    assert 0.0 <= u[0] <= 1.0 and 0.0 <= v[0] <= 1.0


def test_the_top_face_runs_u_along_x_and_v_against_y() -> None:
    half = np.array([1.0, 1.0, 0.005])
    u, v = face_uv(np.array([[-0.9, 0.9, 0.005], [0.9, -0.9, 0.005], [0.5, 0.0, 0.005]]), half)
    assert u == pytest.approx([0.05, 0.95, 0.75]) and v == pytest.approx([0.05, 0.95, 0.5])


@pytest.mark.parametrize("kernel", [True, False], ids=["c_rays", "numpy_rays"])
def test_a_camera_draws_the_board_squares(kernel: bool) -> None:
    sim = Simulation()
    sim.resources = paths()
    sim.spawn_model("board", parse_sdf_model((BOARD / "model.sdf").read_text()), (0, 0, 0.01, 0, 0, 0), base=str(BOARD))
    sim.spawn_sdf("cam", DOWN_CAMERA)
    (config,) = sim.plugins["cam"].configs
    scene = Scene(sim.models, sim.resources)
    camera = CameraSensor(sim.physics, sim.models["cam"], config, ray_kernel=kernel)
    rgb = camera.render(scene).rgb.astype(int)
    assert scene.take_warnings() == []
    # 80 px across 2.5 m: a 0.25 m square is 8 px. Two neighbouring squares near the centre differ, lit vs black;
    # the same colour repeats two squares on.
    centre = rgb[36, 36].sum(), rgb[36, 44].sum(), rgb[36, 52].sum()
    assert max(centre[0], centre[1]) > 300 and min(centre[0], centre[1]) == 0
    assert centre[0] == pytest.approx(centre[2], abs=3)
    # Beyond the board (1.25 m at the picture's edge, the board ends at 1 m): untextured grey.
    red, green, blue = rgb[1, 1]
    assert red == green == blue > 100
