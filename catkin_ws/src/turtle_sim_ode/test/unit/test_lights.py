"""The world's lights through Gazebo's light services (gazebo_ros_api_plugin.cpp: getLightProperties,
setLightProperties, deleteLight) and the cameras shading with what the services leave: a camera publisher asks for
the world's directional light before each frame. A face lit head-on reads its full colour, one lit at 60° from its
normal 0.4 + 0.6 cos 60° of it, and with no sun left 0.4 (sensors.camera's ambient share)."""
import math

import pytest
import rospy
from test_camera import CAMERA_URDF, FACE_X, RED_BOX
from test_camera_topics import FakePublisher

from turtle_sim_ode.models.lights import SUN
from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.ros import camera_topics, periodic
from turtle_sim_ode.sensors.camera import CameraSensor
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.values import WorldError

# A sun shining along +x: straight onto the red box's near face, which looks along -x at the camera.
WORLD = """<sdf version="1.6"><world name="w"><include><uri>model://ground_plane</uri></include>
<light type="directional" name="sun"><direction>1 0 0</direction></light>
<light type="point" name="lamp"><pose>0 0 3 0 0 0</pose><diffuse>0.5 0.5 0.5 1</diffuse></light></world></sdf>"""
KEEP = dict(cast_shadows=False, diffuse=(1, 1, 1, 1), specular=(0, 0, 0, 1), attenuation=(1, 0, 0))


@pytest.fixture
def world(monkeypatch):
    return camera_in(monkeypatch, WORLD)


def camera_in(monkeypatch, text: str, other_lights: bool = False):
    """The red box ahead of a camera in world ``text``, and a publisher of the camera (given the world's other lights
    too where ``other_lights``, as the camera plugins' are)."""
    FakePublisher.made = {}
    monkeypatch.setattr(periodic, "PackedPublisher", FakePublisher)
    sim = Simulation()
    sim.load_world(parse_sdf_world(text))
    urdf = CAMERA_URDF.format(kind="camera", plugin="libgazebo_ros_camera.so", fov=1.047, width=32, height=24, z=0.5)
    sim.spawn_urdf("cam", urdf, (0, 0, 0.05, 0, 0, 0))
    sim.spawn_sdf("red_box", RED_BOX, (FACE_X + 0.25, 0, 0.55, 0, 0, 0))
    camera = CameraSensor(sim.physics, sim.models["cam"], sim.plugins["cam"].cameras[0], sun_direction=(0, 0, -1))
    lights = (lambda: sim.camera_lights) if other_lights else None
    publisher = camera_topics.CameraPublisher(camera, sim.scene, "r", lambda: sim.light_direction, lights)
    FakePublisher.made["r/cam/image_raw"].connections = 1
    return sim, publisher


def centre_red(publisher) -> int:
    publisher.publish(rospy.Time(1, 0), 1.0)
    image = FakePublisher.made["r/cam/image_raw"].messages[-1]
    return image.data[(12 * 32 + 16) * 3]


def test_the_worlds_lights_are_read_with_sdf_defaults(world) -> None:
    sim, _ = world
    assert list(sim.lights) == ["sun", "lamp"]
    lamp = sim.light_properties("lamp")
    assert (lamp.diffuse, lamp.attenuation_constant, lamp.attenuation_linear, lamp.attenuation_quadratic) == (
        (0.5, 0.5, 0.5, 1.0),
        1.0,  # sdformat sdf/1.6/light.sdf: constant 1, linear 1, quadratic 0
        1.0,
        0.0,
    )
    assert sim.light_properties("sun").direction == (1.0, 0.0, 0.0)
    with pytest.raises(WorldError, match="light 'moon' does not exist.*'sun', 'lamp'"):
        sim.light_properties("moon")


def test_model_sun_is_gazebo_models_sun() -> None:
    world = parse_sdf_world(
        '<sdf version="1.6"><world name="w"><include><uri>model://sun</uri></include></world></sdf>'
    )
    # osrf/gazebo_models sun/model.sdf
    assert world.lights == [SUN]
    assert (SUN.diffuse, SUN.attenuation_constant, SUN.attenuation_linear, SUN.attenuation_quadratic) == (
        (0.8, 0.8, 0.8, 1.0),
        0.9,
        0.01,
        0.001,
    )


def test_cameras_shade_with_the_lights_the_services_leave(world) -> None:
    sim, publisher = world
    assert centre_red(publisher) == 255  # head-on: the camera's own (0, 0, -1) was replaced by the world's sun
    sim.set_light_properties("sun", direction=(0.5, 0, -0.866), position=(0, 0, 10), quaternion=(0, 0, 0, 1), **KEEP)
    assert centre_red(publisher) == pytest.approx(255 * (0.4 + 0.6 * 0.5), abs=1)
    sim.delete_light("sun")
    assert sim.light_direction == (0.0, 0.0, 0.0)
    assert centre_red(publisher) == pytest.approx(255 * 0.4, abs=1)  # this publisher is given no other lights


def test_cameras_add_the_point_and_spot_lights_the_services_leave(monkeypatch) -> None:
    """Point and spot lights as sensors.lighting adds them (Ogre's per-pixel diffuse term, see
    test_camera_lights.py); the face's centre is at (1.5, 0, 0.55), its normal -x."""
    torch = '<light type="spot" name="torch"><pose>0.5 0 0.55 0 0 0</pose><direction>1 0 0</direction>'
    torch += "<spot><inner_angle>0.5</inner_angle><outer_angle>1</outer_angle><falloff>1</falloff></spot></light>"
    sim, publisher = camera_in(monkeypatch, WORLD.replace("</world>", torch + "</world>"), other_lights=True)
    sim.delete_light("sun")
    # torch: 1 m ahead of the face, shining at it (diffuse 1, attenuation 1 / (1 + 1 x 1)); lamp: 3 m up,
    # diffuse 0.5, n . l = 1.5 / d, attenuation 1 / (1 + d)
    d = math.hypot(1.5, 3 - 0.55)
    lamp = 0.5 * (1.5 / d) / (1 + d)
    assert centre_red(publisher) == pytest.approx(255 * (0.4 + 0.6 * (0.5 + lamp)), abs=1.5)
    sim.set_light_properties("torch", direction=(0, 0, -1), position=(0.5, 0, 0.55), quaternion=(0, 0, 0, 1), **KEEP)
    assert centre_red(publisher) == pytest.approx(255 * (0.4 + 0.6 * lamp), abs=1.5)  # turned away: the lamp alone
    sim.set_light_properties("lamp", direction=(0, 0, -1), position=(0.5, 0, 0.55), quaternion=(0, 0, 0, 1), **KEEP)
    assert centre_red(publisher) == 255  # the lamp 1 m ahead, attenuation 1 / 1
    sim.delete_light("lamp")
    sim.delete_light("torch")
    assert centre_red(publisher) == pytest.approx(255 * 0.4, abs=1)


def test_the_camera_plugins_publishers_take_the_worlds_other_lights(monkeypatch) -> None:
    """ros.plugins.camera wires Simulation.camera_lights into the publishers it makes."""
    from turtle_sim_ode.ros.plugins import model_interfaces
    from turtle_sim_ode.ros.settings import SimulatorSettings

    monkeypatch.setattr(rospy, "has_param", lambda key: False)
    sim, _ = camera_in(monkeypatch, WORLD)
    (publisher,) = model_interfaces("cam", sim, SimulatorSettings(), None, "r")
    FakePublisher.made["r/cam/image_raw"].connections = 1
    sim.delete_light("sun")
    sim.set_light_properties("lamp", direction=(0, 0, -1), position=(0.5, 0, 0.55), quaternion=(0, 0, 0, 1), **KEEP)
    assert centre_red(publisher) == 255  # the lamp 1 m ahead of the face, attenuation 1 / 1


def test_set_light_properties_normalises_the_quaternion_and_refuses_bad_values(world) -> None:
    sim, _ = world
    sim.set_light_properties("lamp", direction=(0, 0, -1), position=(1, 2, 3), quaternion=(0, 0, 2, 2), **KEEP)
    (x, y, z), (qx, qy, qz, qw) = sim.light_properties("lamp").pose
    assert (x, y, z) == (1, 2, 3) and (qx, qy, qz, qw) == pytest.approx((0, 0, 0.7071068, 0.7071068))
    with pytest.raises(WorldError, match="diffuse must be 4 finite numbers"):
        sim.set_light_properties(
            "lamp", False, (float("nan"), 0, 0, 1), (0, 0, 0, 1), (1, 0, 0), (0, 0, -1), (0, 0, 0), (0, 0, 0, 1)
        )


def test_a_sun_model_on_the_model_path_is_used_else_the_built_in_one(tmp_path) -> None:
    """Gazebo resolves model://sun on its model path: a sun model there stands; without one, the built-in sun."""
    from turtle_sim_ode.models.resources import ResourcePaths

    sun = tmp_path / "models" / "sun"
    sun.mkdir(parents=True)
    (sun / "model.config").write_text('<model><name>sun</name><sdf version="1.6">model.sdf</sdf></model>')
    (sun / "model.sdf").write_text(
        '<sdf version="1.6"><light type="directional" name="sun"><diffuse>0.2 0.3 0.4 1</diffuse>'
        "<direction>0 1 -1</direction></light></sdf>"
    )
    text = '<sdf version="1.6"><world name="w"><include><uri>model://sun</uri><name>day</name></include></world></sdf>'
    sim = Simulation()
    sim.resources = ResourcePaths({}, [str(tmp_path / "models")], [str(tmp_path)])
    sim.load_world(parse_sdf_world(text))
    assert (list(sim.lights), sim.lights["day"].diffuse, sim.light_direction) == (
        ["day"],
        (0.2, 0.3, 0.4, 1.0),
        (0.0, 1.0, -1.0),
    )
    bare = Simulation()
    bare.resources = ResourcePaths({}, [str(tmp_path / "elsewhere")], [str(tmp_path)])
    bare.load_world(parse_sdf_world(text))
    assert bare.lights["day"].diffuse == SUN.diffuse
