"""The ground plane is a model like any other, as in Gazebo: model://ground_plane is the model database's
ground_plane (gazebo_models ground_plane/model.sdf: static, link "link", collision "collision", a plane 100 x 100 with
normal 0 0 1, friction mu 100, mu2 50), loaded by World::Load like every <include> under the <include>'s <name>;
gazebo_ros_api_plugin.cpp lists it (getWorldProperties: every world_->ModelByIndex(i); publishModelStates: every
model), getModelState answers for it and deleteModel removes it. A world without one has no ground at all
(worlds/blank.world falls forever), and a model folder ground_plane on GAZEBO_MODEL_PATH is found before the
database's (gazebo/common/ModelDatabase.cc, GetModelPath: SystemPaths::FindFileURI looks on the model paths first)."""
from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.models.includes import BUILT_IN_GROUND_PLANE
from turtle_sim_ode.models.resources import ResourcePaths
from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.world.simulation import Simulation

HALF = 0.1  # half the crate's side (m)
CRATE = f"""<sdf version="1.6"><model name="crate"><link name="link"><inertial><mass>1</mass>
  <inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
  <collision name="c"><geometry><box><size>{2 * HALF} {2 * HALF} {2 * HALF}</size></box></geometry></collision>
</link></model></sdf>"""


def world(*children: str) -> str:
    return '<sdf version="1.6"><world name="w">%s</world></sdf>' % "".join(children)


GROUND_0 = "<include><uri>model://ground_plane</uri><name>ground_plane_0</name></include>"


def settle(sim: Simulation, seconds: float = 1.0) -> None:
    for _ in range(int(seconds / sim.physics.time_step)):
        sim.step()


def crate_height(sim: Simulation) -> float:
    return sim.get_model_state("crate")[0][2]


def loaded(text: str, paths: ResourcePaths = None) -> Simulation:
    sim = Simulation()
    sim.resources = paths
    sim.load_world(parse_sdf_world(text))
    return sim


def test_the_included_ground_plane_is_a_listed_model_under_the_includes_name() -> None:
    sim = loaded(world(GROUND_0, '<model name="post"><static>true</static><link name="l"/></model>'))
    assert sim.world_properties()["model_names"] == ["ground_plane_0", "post"]  # the world's order
    position, quaternion, linear, angular = sim.get_model_state("ground_plane_0")
    assert (position, quaternion, linear, angular) == ((0, 0, 0), (0, 0, 0, 1), (0, 0, 0), (0, 0, 0))
    properties = sim.model_properties("ground_plane_0")
    assert properties["body_names"] == ["link"] and properties["is_static"]


def test_a_crate_rests_on_it_and_falls_once_it_is_deleted_then_rests_on_a_respawned_one() -> None:
    sim = loaded(world(GROUND_0))
    sim.spawn_sdf("crate", CRATE, (0, 0, 0.5, 0, 0, 0))
    settle(sim)
    assert crate_height(sim) == pytest.approx(HALF, abs=2e-3)
    sim.delete("ground_plane_0")
    assert not sim.physics.has_ground
    settle(sim, 0.5)
    assert crate_height(sim) < -0.5  # nothing holds it: free fall
    sim.spawn_sdf("ground_plane", BUILT_IN_GROUND_PLANE)
    sim.set_model_state("crate", (0, 0, 0.5), (0, 0, 0, 1), (0, 0, 0), (0, 0, 0))
    settle(sim)
    assert crate_height(sim) == pytest.approx(HALF, abs=2e-3)


def test_a_world_without_a_ground_plane_has_no_ground() -> None:
    sim = loaded(world("<include><uri>model://sun</uri></include>"))
    assert sim.world_properties()["model_names"] == [] and not sim.physics.has_ground
    sim.spawn_sdf("crate", CRATE, (0, 0, 0.5, 0, 0, 0))
    settle(sim, 0.5)
    assert crate_height(sim) < -0.5


def test_moving_the_ground_plane_moves_its_plane() -> None:
    sim = loaded(world(GROUND_0))
    sim.set_model_state("ground_plane_0", (0, 0, 0.3), (0, 0, 0, 1), (0, 0, 0), (0, 0, 0))
    sim.spawn_sdf("crate", CRATE, (0, 0, 1.0, 0, 0, 0))
    settle(sim)
    assert crate_height(sim) == pytest.approx(0.3 + HALF, abs=2e-3)


def test_its_friction_is_the_models() -> None:
    sim = loaded(world(GROUND_0))
    surface = sim.physics.surface(sim.physics.ground)
    assert (surface.mu, surface.mu2) == (100.0, 50.0)


def user_model_path(tmp_path: Path, height: float, mu: float) -> ResourcePaths:
    """A ground_plane model folder of the user's (as ~/.gazebo/models would hold), its plane ``height`` up."""
    folder = tmp_path / "models" / "ground_plane"
    folder.mkdir(parents=True)
    (folder / "model.config").write_text(
        '<?xml version="1.0"?><model><name>Ground Plane</name><version>1.0</version>'
        '<sdf version="1.6">model.sdf</sdf></model>'
    )
    (folder / "model.sdf").write_text(
        f"""<?xml version="1.0"?><sdf version="1.6"><model name="ground_plane"><static>true</static>
  <pose>0 0 {height} 0 0 0</pose><link name="link"><collision name="collision">
  <geometry><plane><normal>0 0 1</normal><size>20 20</size></plane></geometry>
  <surface><friction><ode><mu>{mu}</mu><mu2>{mu}</mu2></ode></friction></surface></collision></link></model></sdf>"""
    )
    return ResourcePaths({}, [str(tmp_path / "models")], [str(tmp_path)])


def test_a_ground_plane_on_the_model_path_wins_over_the_built_in_one(tmp_path: Path) -> None:
    sim = loaded(world(GROUND_0), user_model_path(tmp_path, 0.25, 0.5))
    assert sim.get_model_state("ground_plane_0")[0] == pytest.approx((0, 0, 0.25))
    surface = sim.physics.surface(sim.physics.ground)
    assert (surface.mu, surface.mu2) == (0.5, 0.5)
    sim.spawn_sdf("crate", CRATE, (0, 0, 1.0, 0, 0, 0))
    settle(sim)
    assert crate_height(sim) == pytest.approx(0.25 + HALF, abs=2e-3)


@settings(max_examples=12, deadline=None)
@given(
    x=st.floats(-20, 20, allow_subnormal=False),
    y=st.floats(-20, 20, allow_subnormal=False),
    z=st.floats(-2, 2, allow_subnormal=False),
    yaw=st.floats(-3.2, 3.2, allow_subnormal=False),
)
def test_a_ground_moved_anywhere_level_holds_a_crate_just_above_it(x: float, y: float, z: float, yaw: float) -> None:
    """Invariant: a level ground plane moved anywhere holds a crate (at any heading) with its bottom on it."""
    sim = loaded(world(GROUND_0))
    sim.set_model_state("ground_plane_0", (x, y, z), (0, 0, 0, 1), (0, 0, 0), (0, 0, 0))
    sim.spawn_sdf("crate", CRATE, (x + 1, y - 1, z + 0.3, 0, 0, yaw))
    settle(sim, 0.6)
    assert crate_height(sim) == pytest.approx(z + HALF, abs=3e-3)
    assert sim.get_model_state("ground_plane_0")[0] == pytest.approx((x, y, z))
