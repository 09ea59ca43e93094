"""Point and spot lights in the cameras' shading (sensors.lighting), as gazebo-classic's default per-pixel lighting has
them: Ogre's RTShader SGXLib_PerPixelLighting.glsl (SGX_Light_Point_Diffuse, SGX_Light_Spot_Diffuse) adds
diffuse x max(0, n . l) x 1 / (constant + linear d + quadratic d^2) within the range, times the spot factor
clamp((rho - cos(outer / 2)) / (cos(inner / 2) - cos(outer / 2)), 0, 1) ^ falloff (the half-angle cosines from Ogre's
RTShaderSystem PerPixelLighting::updateGpuProgramsParams); gazebo-classic's rendering/Light.cc (Light::Update,
SetAttenuation, SetSpotInnerAngle) hands SDF's <attenuation> and <spot> to Ogre, clamping constant and linear to
[0, 1]. A camera 2 m up looks straight down at the ground; the sun is off, so a pixel reads
255 x grey x (0.4 + 0.6 min(1, light term)) (sensors.camera's ambient share)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.models.lights import Light, parse_light
from turtle_sim_ode.models.materials import GAZEBO_MATERIALS
from turtle_sim_ode.models.text import parse_xml
from turtle_sim_ode.sensors import lighting
from turtle_sim_ode.sensors.camera import AMBIENT, CameraSensor
from turtle_sim_ode.world.simulation import Simulation

GREY = GAZEBO_MATERIALS["Gazebo/Grey"][0]
HEIGHT = 2.0
SIZE = 65  # odd: the middle pixel looks straight down at the origin
DOWN_URDF = """<robot name="cam"><link name="base"><inertial><mass value="1"/>
<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
<gazebo reference="base"><static>true</static><sensor type="camera" name="cam"><update_rate>15</update_rate>
<pose>0 0 {z} 0 1.5707963 0</pose><camera><horizontal_fov>1.2</horizontal_fov>
<image><width>{size}</width><height>{size}</height></image><clip><near>0.05</near><far>10</far></clip></camera>
<plugin name="c" filename="libgazebo_ros_camera.so"><cameraName>cam</cameraName></plugin></sensor></gazebo></robot>"""


def lamp(**fields) -> Light:
    return Light("lamp", **{"pose": ((0.0, 0.0, 1.0), (0.0, 0.0, 0.0, 1.0)), **fields})


def looking_down(ray_kernel: bool = True):
    sim = Simulation()
    sim.spawn_urdf("cam", DOWN_URDF.format(z=HEIGHT - 0.05, size=SIZE), (0, 0, 0.05, 0, 0, 0))
    return sim, CameraSensor(sim.physics, sim.models["cam"], sim.plugins["cam"].cameras[0], ray_kernel=ray_kernel)


@pytest.fixture(scope="module", params=[True, False], ids=["ray_kernel", "numpy"])
def down(request):
    return looking_down(request.param)


@pytest.fixture(scope="module")
def down_default():
    """One camera for the generated test (Hypothesis keeps one example database per test function, not per
    parameter); the relighting is shared by both ray casters."""
    return looking_down()


def shot(down, lights):
    """The picture with the sun off and ``lights``; the ground point of each pixel (H, W, 3)."""
    sim, camera = down
    camera.light_from((0.0, 0.0, 0.0), lights)
    frame = camera.render(sim.scene)
    origin, rotation = frame.pose
    points, _ = lighting.surface(frame.depth.astype(float), (camera._u, camera._v))
    return frame.rgb[:, :, 0].astype(float), np.stack(points, axis=-1).astype(float) @ rotation.T + origin


def term(red: np.ndarray) -> np.ndarray:
    """The light term a pixel shows (sun off): (red / (255 grey) - ambient) / (1 - ambient)."""
    return (red / (255.0 * GREY) - AMBIENT) / (1.0 - AMBIENT)


def test_the_ground_below_a_point_light_is_lit_as_ogres_attenuation_predicts(down) -> None:
    light = lamp(attenuation_constant=1.0, attenuation_linear=0.5, attenuation_quadratic=0.2)
    red, ground = shot(down, [light])
    middle = SIZE // 2
    assert ground[middle, middle] == pytest.approx((0, 0, 0), abs=1e-6)
    far = (middle, middle + 20)
    x, y, _ = ground[far]
    distance = math.sqrt(x * x + y * y + 1.0)
    # SGX_Light_Point_Diffuse: n . l x 1 / (c + l d + q d^2); under the lamp n . l = 1 and d = 1.
    below = 1.0 / (1.0 + 0.5 + 0.2)
    aside = (1.0 / distance) / (1.0 + 0.5 * distance + 0.2 * distance**2)
    tolerance = 1.5 / (255.0 * GREY * (1.0 - AMBIENT))  # the ray casters' rounding, scaled up by the relighting
    assert term(red[middle, middle]) == pytest.approx(below, abs=tolerance)
    assert term(red[far]) == pytest.approx(aside, abs=tolerance)
    assert red[middle, middle] > red[far]
    assert term(red[middle, middle]) / term(red[far]) == pytest.approx(below / aside, rel=0.03)


def test_beyond_the_range_a_point_light_reaches_nothing(down) -> None:
    red, ground = shot(down, [lamp(attenuation_range=1.2)])
    distance = np.sqrt((ground[:, :, :2] ** 2).sum(axis=2) + 1.0)
    ambient_only = np.floor(255.0 * GREY * AMBIENT + 0.5)
    assert (red[distance > 1.21] == ambient_only).all() and (red[distance < 1.19] > ambient_only).all()


def test_a_spot_light_lights_its_cone_and_nothing_beyond_the_outer_angle(down) -> None:
    # Full cone angles, as <spot> gives them and Ogre's setSpotlightRange takes them: 0.4 and 0.8 rad.
    spot = lamp(type="spot", spot_inner_angle=0.4, spot_outer_angle=0.8, spot_falloff=1.0, attenuation_linear=0.0)
    red, ground = shot(down, [spot])
    off_axis = np.arctan(np.hypot(ground[:, :, 0], ground[:, :, 1]) / 1.0)
    ambient_only = np.floor(255.0 * GREY * AMBIENT + 0.5)
    inside, rim, outside = off_axis < 0.19, (off_axis > 0.21) & (off_axis < 0.39), off_axis > 0.41
    assert inside.any() and rim.any() and outside.any()
    assert (red[outside] == ambient_only).all()
    # inside the inner cone: n . l x 1 / constant, n . l = cos(off axis)
    expected = np.cos(off_axis[inside])
    assert term(red[inside]) == pytest.approx(expected, abs=1.5 / (255.0 * GREY * 0.6))
    assert (red[rim] > ambient_only).all() and red[rim].max() < red[inside].min() + 1


def test_the_spot_element_is_read_and_the_light_points_along_its_pose() -> None:
    element = parse_xml(
        '<light type="spot" name="s"><pose>0 0 1 0 1.5707963 0</pose><direction>0 0 -1</direction>'
        "<spot><inner_angle>0.1</inner_angle><outer_angle>0.5</outer_angle><falloff>2</falloff></spot></light>",
        "light",
    )
    light = parse_light(element)
    assert (light.spot_inner_angle, light.spot_outer_angle, light.spot_falloff) == (0.1, 0.5, 2.0)
    # the direction is in the light's frame (rendering/Light.cc LoadFromMsg, UpdateFromMsg: SetPosition and
    # SetRotation of the pose on the light's node, whose child the Ogre light's direction is): pitched by 90
    # degrees, -z becomes -x
    assert lighting.PixelLight.of(light).toward == pytest.approx((-1, 0, 0), abs=1e-6)


def test_light_tcc_clamps_constant_and_linear_to_one() -> None:
    light = lighting.PixelLight.of(lamp(attenuation_constant=5.0, attenuation_linear=-2.0, attenuation_quadratic=3.0))
    assert light.attenuation == (10.0, 1.0, 0.0, 3.0)


def centimetres(low: int, high: int) -> st.SearchStrategy[float]:
    # integer steps: bounded floats here tripped Hypothesis 6.67's data_too_large health check at random
    return st.integers(low, high).map(lambda n: n / 100.0)


def ground_points(count: int = 60) -> np.ndarray:
    return np.stack((np.linspace(0.0, 6.0, count), np.zeros(count), np.zeros(count)), axis=1)


@settings(max_examples=80, deadline=None)
@given(
    height=st.floats(0.05, 5.0),
    constant=st.floats(-1.0, 2.0),
    linear=st.floats(-1.0, 2.0),
    quadratic=st.floats(0.0, 3.0),
    range_=st.floats(0.1, 30.0),
    kind=st.sampled_from(["point", "spot"]),
    inner=st.floats(0.0, 3.0),
    outer=st.floats(0.0, 3.0),
    falloff=st.floats(0.0, 5.0),
    diffuse=st.tuples(st.floats(-1.0, 2.0), st.floats(-1.0, 2.0), st.floats(-1.0, 2.0)),
)
def test_a_lights_term_on_the_ground_never_grows_with_distance_nor_goes_negative_or_nan(
    height, constant, linear, quadratic, range_, kind, inner, outer, falloff, diffuse
) -> None:
    light = Light(
        "l",
        type=kind,
        diffuse=diffuse + (1.0,),
        attenuation_range=range_,
        attenuation_constant=constant,
        attenuation_linear=linear,
        attenuation_quadratic=quadratic,
        spot_inner_angle=inner,
        spot_outer_angle=outer,
        spot_falloff=falloff,
        pose=((0.0, 0.0, height), (0.0, 0.0, 0.0, 1.0)),
    )
    points = ground_points()
    terms = np.stack(lighting.light_terms(points.T, (0.0, 0.0, 1.0), [lighting.PixelLight.of(light)]), axis=1)
    assert np.isfinite(terms).all() and (terms >= 0.0).all()
    # farther along the ground, farther from the light and more off the spot's axis: never brighter
    assert (np.diff(terms, axis=0) <= 1e-9 * (1.0 + terms[:-1])).all()


@settings(max_examples=15, deadline=None)
@given(
    x=centimetres(-100, 100),
    y=centimetres(-100, 100),
    z=centimetres(20, 180),
    linear=centimetres(0, 100),
    quadratic=centimetres(0, 200),
)
def test_pictures_of_the_ground_darken_away_from_a_point_light(down_default, x, y, z, linear, quadratic) -> None:
    light = lamp(attenuation_linear=linear, attenuation_quadratic=quadratic, pose=((x, y, z), (0.0, 0.0, 0.0, 1.0)))
    red, ground = shot(down_default, [light])
    distance = np.linalg.norm(ground - (x, y, z), axis=2).reshape(-1)
    order = np.argsort(distance)
    brightness = red.reshape(-1)[order]
    # no pixel brighter than a nearer one, beyond the rounding of the picture (2 levels)
    brightest_beyond = np.maximum.accumulate(brightness[::-1])[::-1]
    assert (brightest_beyond <= brightness + 2.0).all()
    assert red.min() >= np.floor(255.0 * GREY * AMBIENT + 0.5)


def test_without_other_lights_the_picture_is_the_ray_casters(down) -> None:
    sim, camera = down
    camera.light_from(None, [])
    plain = camera.render(sim.scene).rgb.copy()
    camera.light_from(None, [lamp(diffuse=(0.0, 0.0, 0.0, 1.0))])
    assert (camera.render(sim.scene).rgb == plain).all()
