"""world.viewer_scene and ros.viewer_config: the visuals the viewer draws (shape, pose, colour as Gazebo draws it),
what changes update by update, and the first view from the world's user camera."""
from __future__ import annotations

import math
from typing import Dict, Tuple

import pytest
from conftest import MESH_PACKAGE, TURTLEBOT_URDF, fixture_paths
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from visualization_msgs.msg import Marker

from turtle_sim_ode.models.transforms import Transform, compose, quat_multiply
from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.ros.scene_markers import marker_of
from turtle_sim_ode.ros.viewer_config import FIXED_FRAME, SCENE_TOPIC, rviz_config
from turtle_sim_ode.world.simulation import Simulation
from turtle_sim_ode.world.user_camera import DEFAULT_USER_CAMERA, MAX_ORBIT_PITCH, orbit_view
from turtle_sim_ode.world.viewer_scene import GROUND_PLANE, OWN_COLOURS, SceneTracker, SceneUpdate


def box_model(name: str = "box", visual: str = "", static: bool = False) -> str:
    """An SDF box whose visual carries ``visual`` (material tags)."""
    return f"""<sdf version="1.6"><model name="{name}"><static>{str(static).lower()}</static><link name="body">
      <inertial><mass>1</mass></inertial>
      <visual name="look"><pose>0 0 0.1 0 0 0</pose><geometry><box><size>0.3 0.2 0.1</size></box></geometry>{visual}
      </visual>
      <collision name="shape"><geometry><box><size>0.3 0.2 0.1</size></box></geometry></collision>
    </link></model></sdf>"""


def mesh_model(uri: str, material: str = "") -> str:
    return f"""<sdf version="1.6"><model name="m"><static>true</static><link name="l">
      <visual name="v"><geometry><mesh><uri>{uri}</uri><scale>2 2 2</scale></mesh></geometry>{material}</visual>
      <visual name="w"><geometry><sphere><radius>0.1</radius></sphere></geometry></visual>
    </link></model></sdf>"""


URDF_RED = """<robot name="r">
  <material name="teal"><color rgba="0 0.5 0.5 0.25"/></material>
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial><visual><geometry><cylinder radius="0.1" length="0.4"/></geometry>
    <material name="teal"/></visual></link>
  <link name="top"><visual><geometry><sphere radius="0.05"/></geometry></visual></link>
  <joint name="j" type="fixed"><parent link="base"/><child link="top"/><origin xyz="0 0 0.3"/></joint>
  <gazebo reference="top"><material>Gazebo/Red</material></gazebo>
</robot>"""


def scene_of(sim: Simulation) -> SceneUpdate:
    tracker = SceneTracker(sim.resources)
    return tracker.update(tracker.read_poses(sim.models, sim.physics.has_own_ground))


def only_visuals(update: SceneUpdate, model: str):  # type: ignore[no-untyped-def]
    return [visual for _, visual, _ in update.added[model]]


def test_colours_as_gazebo_draws_them() -> None:
    """SDF diffuse with <transparency>, a Gazebo/* script, a URDF named material's rgba (its alpha too), and a
    <gazebo reference> material over the URDF's (gazebo_ros_pkgs urdf2gazebo: the <gazebo> material wins)."""
    sim = Simulation()
    sim.spawn_sdf(
        "diffuse",
        box_model("diffuse", "<material><diffuse>1 0 0 1</diffuse></material><transparency>0.5" "</transparency>"),
        (0, 0, 0, 0, 0, 0),
    )
    script = "<material><script><name>Gazebo/Blue</name></script></material>"
    sim.spawn_sdf("script", box_model("script", script), (2, 0, 0, 0, 0, 0))
    sim.spawn_sdf("plain", box_model("plain"), (4, 0, 0, 0, 0, 0))
    sim.spawn_urdf("urdf", URDF_RED, (6, 0, 0, 0, 0, 0))
    update = scene_of(sim)
    assert only_visuals(update, "diffuse")[0].rgba == (1.0, 0.0, 0.0, 0.5)
    assert only_visuals(update, "script")[0].rgba == (0.0, 0.0, 1.0, 1.0)
    assert only_visuals(update, "plain")[0].rgba == (0.7, 0.7, 0.7, 1.0)  # Gazebo's default grey
    base, top = only_visuals(update, "urdf")
    assert base.rgba == (0.0, 0.5, 0.5, 0.25) and base.shape == "cylinder" and base.size == (0.2, 0.2, 0.4)
    assert top.rgba == (1.0, 0.0, 0.0, 1.0) and top.size == (0.1, 0.1, 0.1)
    assert update.warnings == []


def test_world_poses_compose_link_and_visual_origin() -> None:
    sim = Simulation()
    sim.spawn_sdf("box", box_model(static=True), (1.0, 2.0, 0.5, 0.0, 0.0, math.pi / 2))
    ((_, visual, (position, quaternion)),) = scene_of(sim).added["box"]
    assert visual.shape == "box" and visual.size == (0.3, 0.2, 0.1)
    assert position == pytest.approx((1.0, 2.0, 0.6))
    assert quaternion == pytest.approx((math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4)))


def test_meshes_keep_their_own_colours_and_scale() -> None:
    """A Collada mesh without a material of its own is drawn in the file's colours; an STL one in Gazebo's grey;
    one with a material in that material's colour."""
    sim = Simulation()
    sim.resources = fixture_paths()
    sim.spawn_sdf("m", mesh_model("model://tso_y_up_wall/meshes/wall_inches_y_up.dae"), (0, 0, 0, 0, 0, 0))
    mesh, sphere = only_visuals(scene_of(sim), "m")
    assert mesh.shape == "mesh" and mesh.size == (2.0, 2.0, 2.0) and mesh.rgba == OWN_COLOURS
    assert mesh.mesh_path == str(MESH_PACKAGE / "models" / "tso_y_up_wall" / "meshes" / "wall_inches_y_up.dae")
    assert sphere.shape == "sphere"
    sim.delete("m")
    sim.spawn_sdf("m", mesh_model("package://tso_mesh_worlds/meshes/plate.stl"), (0, 0, 0, 0, 0, 0))
    assert only_visuals(scene_of(sim), "m")[0].rgba == (0.7, 0.7, 0.7, 1.0)
    sim.delete("m")
    green = "<material><ambient>0 1 0 1</ambient></material>"
    sim.spawn_sdf("m", mesh_model("package://tso_mesh_worlds/meshes/green_block.dae", green), (0, 0, 0, 0, 0, 0))
    assert only_visuals(scene_of(sim), "m")[0].rgba == (0.0, 1.0, 0.0, 1.0)


def test_mesh_markers_use_the_files_materials_only_without_a_visual_material() -> None:
    """rviz (default_plugin/markers/mesh_resource_marker.cpp, MeshResourceMarker::onNewMessage) keeps a mesh's
    embedded materials only with mesh_use_embedded_materials and colour 0 0 0 0; with another colour it draws them
    tinted (a second pass at half opacity). Gazebo (rendering/Visual.cc, Visual::Load -> SetMaterial) replaces them
    with the visual's material: turtlebot3_world's wall.dae is its file's grey-blue, Gazebo/FlatBlack on screen."""
    sim = Simulation()
    sim.resources = fixture_paths()
    flat_black = "<material><script><name>Gazebo/FlatBlack</name></script></material>"
    for material, embedded, colour in [("", True, OWN_COLOURS), (flat_black, False, (0.1, 0.1, 0.1, 1.0))]:
        sim.spawn_sdf("m", mesh_model("package://tso_mesh_worlds/meshes/green_block.dae", material), (0,) * 6)
        mesh = only_visuals(scene_of(sim), "m")[0]
        marker = marker_of("m", 0, mesh)
        assert marker.type == Marker.MESH_RESOURCE and marker.mesh_resource == "file://" + mesh.mesh_path
        assert marker.mesh_use_embedded_materials is embedded
        assert (marker.color.r, marker.color.g, marker.color.b, marker.color.a) == pytest.approx(colour)
        sim.delete("m")


@pytest.mark.parametrize(
    "uri, why",
    [
        ("package://tso_mesh_worlds/meshes/missing.dae", "missing.dae"),
        ("package://tso_mesh_worlds/package.xml", ".xml"),
        ("package://tso_mesh_worlds/models/tso_mesh_room/model.config", ".config"),
    ],
)
def test_a_mesh_that_cannot_be_drawn_leaves_the_rest(uri: str, why: str) -> None:
    sim = Simulation()
    sim.resources = fixture_paths()
    sim.spawn_sdf("m", mesh_model("package://tso_mesh_worlds/meshes/plate.stl"), (0, 0, 0, 0, 0, 0))
    sim.delete("m")
    # The collision loader does not read visual meshes: the model spawns, and the viewer warns once.
    sim.spawn_sdf("m", mesh_model(uri), (0, 0, 0, 0, 0, 0))
    update = scene_of(sim)
    assert [visual.shape for visual in only_visuals(update, "m")] == ["sphere"]
    (warning,) = update.warnings
    assert "model 'm'" in warning and "link 'l'" in warning and uri in warning and why in warning


def test_the_simulators_own_ground_is_drawn_and_a_worlds_ground_is_its_models_visual() -> None:
    # Without a world the simulator keeps a ground of its own, drawn as Gazebo's ground_plane model.
    sim = Simulation()
    update = scene_of(sim)
    ((_, ground, (position, _)),) = update.added[GROUND_PLANE]
    assert ground.size[:2] == (100.0, 100.0) and position[2] + ground.size[2] / 2 == pytest.approx(0.0)
    # A world's ground is a model (model://ground_plane under its include's name): drawn once, from its visual.
    sim = Simulation()
    sim.load_world(
        parse_sdf_world(
            "<sdf version='1.6'><world name='w'><include><uri>model://ground_plane</uri><name>ground_plane_0</name>"
            "</include></world></sdf>"
        )
    )
    update = scene_of(sim)
    assert set(update.added) == {"ground_plane_0"}
    # A world without a ground plane has no ground, and none is drawn.
    sim = Simulation()
    sim.load_world(parse_sdf_world("<sdf version='1.6'><world name='w'></world></sdf>"))
    assert scene_of(sim).added == {}


def test_only_what_changed_is_sent() -> None:
    """A falling box moves; a static one does not, until set_model_state moves it (paused: no step at all); a
    model deleted and spawned again under its name is removed and added."""
    sim = Simulation()
    sim.spawn_sdf("falling", box_model("falling"), (0, 0, 1, 0, 0, 0))
    sim.spawn_sdf("still", box_model("still", static=True), (3, 0, 0, 0, 0, 0))
    tracker = SceneTracker(None)
    first = tracker.update(tracker.read_poses(sim.models))
    assert set(first.added) == {"falling", "still"} and not first.moved
    assert tracker.update(tracker.read_poses(sim.models)).empty()
    for _ in range(10):
        sim.step()
    update = tracker.update(tracker.read_poses(sim.models))
    assert set(update.moved) == {"falling"} and not update.added and not update.removed
    sim.set_model_state("still", (3.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    assert set(tracker.update(tracker.read_poses(sim.models)).moved) == {"still"}
    sim.delete("falling")
    sim.spawn_sdf("falling", box_model("falling"), (0, 0, 1, 0, 0, 0))
    update = tracker.update(tracker.read_poses(sim.models))
    assert update.removed == {"falling": 1} and set(update.added) == {"falling"}
    sim.delete("still")
    assert tracker.update(tracker.read_poses(sim.models)).removed == {"still": 1}


Shown = Dict[Tuple[str, int], Transform]

operations = st.lists(
    st.tuples(
        st.sampled_from(["spawn", "move", "delete", "step"]),
        st.sampled_from(["a", "b", "c"]),
        st.tuples(
            *[st.floats(-5, 5).map(lambda v: round(v, 6))] * 2,
            st.floats(0, 2).map(lambda v: round(v, 6)),
            st.floats(-math.pi, math.pi).map(lambda v: round(v, 6)),
        ),
    ),
    max_size=12,
)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(operations)
def test_a_viewer_that_keeps_what_it_is_sent_sees_the_world(steps) -> None:  # type: ignore[no-untyped-def]
    """Applying every update to what a viewer keeps (as rviz's MarkerArray display does) gives, after each
    operation, exactly the visuals of the models there, at their links' poses composed with their origins."""
    sim = Simulation()
    tracker = SceneTracker(None)
    shown: Shown = {}
    for action, name, (x, y, z, yaw) in steps:
        if action == "spawn" and name not in sim.models:
            sim.spawn_sdf(name, box_model(name, static=z > 1), (x, y, z, 0, 0, yaw))
        elif action == "move" and name in sim.models:
            quaternion = (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))
            sim.set_model_state(name, (x, y, z), quaternion)
        elif action == "delete" and name in sim.models:
            sim.delete(name)
        elif action == "step":
            sim.step()
        update = tracker.update(tracker.read_poses(sim.models))
        for model, count in update.removed.items():
            for index in range(count):
                del shown[(model, index)]
        for changes in (update.added, update.moved):
            for model, placed in changes.items():
                shown.update(((model, index), pose) for index, _, pose in placed)
        expected = set()
        for model_name, model in sim.models.items():
            link_pose = model.link_transform("body")
            visual = model.robot.links["body"].visuals[0]
            expected.add((model_name, 0))
            want = compose(link_pose, ((0.0, 0.0, 0.1), (1.0, 0.0, 0.0, 0.0)))
            got = shown[(model_name, 0)]
            assert visual.name == "look"
            assert got[0] == pytest.approx(want[0], abs=1e-4) and got[1] == pytest.approx(want[1], abs=1e-4)
        assert set(shown) == expected


def camera_position(view) -> Tuple[float, float, float]:  # type: ignore[no-untyped-def]
    x, y, z = view.focal_point
    c = math.cos(view.pitch)
    return (
        x + view.distance * c * math.cos(view.yaw),
        y + view.distance * c * math.sin(view.yaw),
        z + view.distance * math.sin(view.pitch),
    )


def test_first_views() -> None:
    """Gazebo's default user camera (5, -5, 2) looks at the origin (gazebo-classic gui/MainWindow_TEST.cc:
    startPose (5, -5, 2, 0, 0.275643, 2.35619)); turtlebot3_world's (0.8 0 12 0 1.5708 0) looks straight down at
    (0.8, 0) with +x up on the screen, as Gazebo shows it (rviz's orbit: the camera behind its focal point, yaw pi)."""
    default = orbit_view(DEFAULT_USER_CAMERA)
    assert camera_position(default) == pytest.approx((5.0, -5.0, 2.0), abs=1e-6)
    assert math.dist(default.focal_point, (0, 0, 0)) < 0.1
    top = orbit_view((0.8, 0.0, 12.0, 0.0, 1.5708, 0.0))
    assert top.focal_point == pytest.approx((0.8, 0.0, 0.0), abs=1e-3) and top.distance == pytest.approx(12.0)
    assert top.pitch == MAX_ORBIT_PITCH and abs(top.yaw) == pytest.approx(math.pi)


@given(
    st.tuples(
        st.floats(-20, 20),
        st.floats(-20, 20),
        st.floats(0.1, 20),
        st.just(0.0),
        st.floats(-1.5, 1.5),
        st.floats(-math.pi, math.pi),
    )
)
def test_the_orbit_view_sits_where_the_camera_is(pose) -> None:  # type: ignore[no-untyped-def]
    view = orbit_view(pose)
    assert camera_position(view) == pytest.approx(pose[:3], abs=1e-6)
    assert view.distance >= 1.0


def test_world_user_camera_and_rviz_config() -> None:
    world = parse_sdf_world((MESH_PACKAGE / "worlds" / "viewer_arena.world").read_text())
    assert world.user_camera is not None and world.user_camera.xyz == (0.8, 0.0, 12.0)
    config = rviz_config(list(world.user_camera.xyz) + list(world.user_camera.rpy))
    manager = config["Visualization Manager"]
    assert manager["Global Options"]["Fixed Frame"] == FIXED_FRAME
    markers = [d for d in manager["Displays"] if d["Class"] == "rviz/MarkerArray"]
    assert markers[0]["Marker Topic"] == SCENE_TOPIC and markers[0]["Enabled"]
    assert manager["Views"]["Current"]["Class"] == "rviz/Orbit"
    assert manager["Views"]["Current"]["Distance"] == pytest.approx(12.0)
    assert parse_sdf_world((MESH_PACKAGE / "worlds" / "mesh_room.world").read_text()).user_camera is not None


def test_joints_move_their_links() -> None:
    """A wheel turned by set_model_configuration is sent as moved, turned by that angle about its axle; the
    chassis, which stays, is not."""
    sim = Simulation()
    sim.spawn_urdf("robot", TURTLEBOT_URDF, (0, 0, 0, 0, 0, 0))
    for _ in range(200):  # settle on the ground
        sim.step()
    tracker = SceneTracker(None)
    first = tracker.update(tracker.read_poses(sim.models))
    wheel_before = {visual.link: pose for _, visual, pose in first.added["robot"]}["wheel_left_link"]
    sim.set_model_configuration("robot", ["wheel_left_joint"], [1.0])
    update = tracker.update(tracker.read_poses(sim.models))
    moved = {visual.link: pose for _, visual, pose in update.moved["robot"]}
    assert "wheel_left_link" in moved and "base_link" not in moved
    turned = quat_multiply(conjugate(wheel_before[1]), moved["wheel_left_link"][1])
    assert 2 * math.acos(min(1.0, abs(turned[0]))) == pytest.approx(1.0, abs=0.02)


def conjugate(q: Tuple[float, float, float, float]) -> Tuple[float, float, float, float]:
    return (q[0], -q[1], -q[2], -q[3])
