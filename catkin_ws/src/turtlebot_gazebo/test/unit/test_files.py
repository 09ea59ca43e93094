"""turtlebot_gazebo's files carry upstream's interface. Expected values from turtlebot/turtlebot_simulator (melodic)
turtlebot_gazebo: launch/turtlebot_world.launch (args gui and world_file, the TURTLEBOT_* variables and defaults,
depthimage_to_laserscan's params and remaps), launch/includes/kobuki.launch.xml (model mobile_base, the robot file
name pattern, the multiplexer's output remap), env-hooks/25.turtlebot-gazebo.sh.em, worlds/playground.world (model
names and poses, the first view); and turtlebot/turtlebot (melodic) turtlebot_bringup/param/mux.yaml (the inputs)."""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import yaml

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
LAUNCH = PACKAGE_ROOT / "launch"


def launch(name: str) -> ET.Element:
    return ET.parse(str(LAUNCH / name)).getroot()


def args(root: ET.Element) -> dict:
    return {a.get("name"): a.get("default", a.get("value")) for a in root.findall("arg")}


def test_turtlebot_world_args_and_environment():
    found = args(launch("turtlebot_world.launch"))
    assert found["gui"] == "true"
    assert "TURTLEBOT_GAZEBO_WORLD_FILE" in found["world_file"]
    assert found["base"] == "$(optenv TURTLEBOT_BASE kobuki)"
    assert found["stacks"] == "$(optenv TURTLEBOT_STACKS hexagons)"
    assert found["3d_sensor"] == "$(optenv TURTLEBOT_3D_SENSOR kinect)"
    assert found["battery"] == "$(optenv TURTLEBOT_BATTERY /proc/acpi/battery/BAT0)"


def test_fake_laser_as_upstream():
    node = launch("includes/depth_scan.launch.xml").find("node")
    params = {p.get("name"): p.get("value") for p in node.findall("param")}
    assert params == {"scan_height": "10", "output_frame_id": "camera_depth_frame", "range_min": "0.45"}
    remaps = {r.get("from"): r.get("to") for r in node.findall("remap")}
    assert remaps == {"image": "/camera/depth/image_raw", "scan": "/scan"}


def test_kobuki_include_spawns_mobile_base_behind_the_mux():
    root = launch("includes/kobuki.launch.xml")
    assert "robots/$(arg base)_$(arg stacks)_$(arg 3d_sensor).urdf.xacro" in args(root)["urdf_file"]
    nodes = {n.get("name"): n for n in root.findall("node")}
    spawn = nodes["spawn_turtlebot_model"].get("args")
    assert spawn.startswith("$(optenv ROBOT_INITIAL_POSE)") and "-model mobile_base" in spawn and "-unpause" in spawn
    mux = nodes["cmd_vel_mux"]
    assert {r.get("from"): r.get("to") for r in mux.findall("remap")} == {
        "cmd_vel_mux/output": "mobile_base/commands/velocity"
    }


def test_mux_inputs_are_turtlebot_bringups():
    config = yaml.safe_load((PACKAGE_ROOT / "param" / "mux.yaml").read_text())
    assert [(s["name"], s["topic"], s["timeout"], s["priority"]) for s in config["subscribers"]] == [
        ("Safe reactive controller", "input/safety_controller", 0.2, 10),
        ("Teleoperation", "input/teleop", 1.0, 7),
        ("Switch", "input/switch", 1.0, 6),
        ("Navigation", "input/navi", 1.0, 5),
    ]


def test_env_hook_defaults_the_world_file():
    hook = (PACKAGE_ROOT / "env-hooks" / "25.turtlebot-gazebo.sh.em").read_text()
    assert ": ${TURTLEBOT_GAZEBO_WORLD_FILE:=" in hook and "export TURTLEBOT_GAZEBO_WORLD_FILE" in hook


# name: (x, y, yaw) in upstream's playground.world, in its order, where Gazebo loads them (World::Load applies the
# world's <state>, which turns the Dumpster from its model's yaw -0.3 to 0)
UPSTREAM_PLAYGROUND = {
    "bookshelf": (0.0, 1.53026, 0.0),
    "jersey_barrier": (-4.0, -1.0, -0.7),
    "ground_plane_0": (0.497681, 0.0, 0.0),
    "unit_cylinder_1": (-2.0, -3.4888, 0.0),
    "Dumpster": (1.0, -3.44458, 0.0),
    "cube_20k": (1.41131, -1.0, 0.9),
}


def pose_of(element: ET.Element) -> tuple:
    x, y, _z, _r, _p, yaw = (float(v) for v in element.findtext("pose").split())
    return x, y, yaw


def test_playground_has_upstreams_models_near_their_poses():
    world = ET.parse(str(PACKAGE_ROOT / "worlds" / "playground.world")).getroot().find("world")
    models = {
        (m.get("name") if m.tag == "model" else m.findtext("name")): pose_of(m)
        for m in world
        if m.tag in ("model", "include") and m.findtext("uri") != "model://sun"
    }
    assert list(models) == list(UPSTREAM_PLAYGROUND)  # get_world_properties lists them in this order
    for name, (x, y, yaw) in UPSTREAM_PLAYGROUND.items():
        mx, my, myaw = models[name]
        assert math.hypot(mx - x, my - y) < 1e-6 and abs(myaw - yaw) < 1e-6, name
    cube = [i for i in world.findall("include") if i.findtext("name") == "cube_20k"][0]
    model = PACKAGE_ROOT / "models" / cube.findtext("uri").replace("model://", "")
    assert "<mesh>" in (model / "model.sdf").read_text()  # the mesh cube collides as a mesh


def test_playground_opens_on_upstreams_first_view():
    """upstream's <gui><camera name='user_camera'><pose>: the viewer's first view looks straight down from 27.6 m."""
    world = ET.parse(str(PACKAGE_ROOT / "worlds" / "playground.world")).getroot().find("world")
    camera = world.find("gui/camera")
    assert camera.get("name") == "user_camera"
    pose = [float(v) for v in camera.findtext("pose").split()]
    assert pose == pytest.approx([1.33336, -0.422442, 27.6101, 3e-06, 1.5698, 3.04015])


@pytest.mark.parametrize("name", ["turtlebot_world.launch", "turtlebot_empty_world.launch"])
def test_launch_files_parse(name):
    assert launch(name).tag == "launch"
