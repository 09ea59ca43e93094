"""A world file's <state> applied as Gazebo applies it on load (gazebo-classic gazebo/physics/World.cc, World::Load:
the first <state> through World::SetState: SetSimTime, then Model::SetState for each model: the model's world pose,
then each link's world pose, linear and angular velocity as Link::SetState sets them; lights' poses; models the world
lacks are an error Gazebo logs and passes over). Model::Reset returns a model to its initial pose, which SetState
does not change: reset_world puts the models where the world's <model> tags put them."""
import math

import pytest
from conftest import PACKAGE_ROOT

from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.world.simulation import Simulation

WORLD = (PACKAGE_ROOT / "test" / "worlds" / "saved_state.world").read_text()


@pytest.fixture
def loaded():
    sim = Simulation()
    warnings = sim.load_world(parse_sdf_world(WORLD))
    return sim, warnings


def yaw_of(quaternion) -> float:
    x, y, z, w = quaternion
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def test_sim_time_starts_at_the_saved_one(loaded) -> None:
    sim, _ = loaded
    assert sim.sim_time == pytest.approx(12.5)
    sim.step()
    assert sim.sim_time == pytest.approx(12.501)


def test_models_and_links_are_where_the_state_puts_them(loaded) -> None:
    sim, _ = loaded
    position, quaternion, linear, angular = sim.get_link_state("crate::link")
    assert position == pytest.approx((2, 1, 0.4), abs=1e-9)
    assert yaw_of(quaternion) == pytest.approx(1.5708)
    assert linear == pytest.approx((0.5, 0, 0)) and angular == pytest.approx((0, 0, 0.25))
    # a static model moves with its model pose
    position, quaternion, _, _ = sim.get_model_state("wall")
    assert position == pytest.approx((-1, -4, 0.5)) and yaw_of(quaternion) == pytest.approx(0.7854)


def test_lights_take_their_saved_pose(loaded) -> None:
    sim, _ = loaded
    assert sim.light_properties("sun").pose[0] == pytest.approx((1, 2, 10))


def test_what_the_world_lacks_is_named_and_the_built_in_ground_is_not(loaded) -> None:
    _, warnings = loaded
    assert [w for w in warnings if "<state>" in w] == [
        "<state> has model 'lost_model', which the world does not have: ignored"
    ]


def test_reset_world_returns_to_the_world_files_poses(loaded) -> None:
    sim, _ = loaded
    sim.reset_world()
    assert sim.get_model_state("crate")[0] == pytest.approx((0, 0, 0.2), abs=1e-9)
    assert sim.get_model_state("wall")[0] == pytest.approx((0, 3, 0.5), abs=1e-9)


NESTED = """<sdf version="1.6"><world name="w">
  <include><uri>model://ground_plane</uri></include>
  <model name="cart"><pose>0 0 0.5 0 0 0</pose>
    <link name="body"><inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia>
      </inertial></link>
    <model name="pod"><pose>1 0 0 0 0 0</pose>
      <link name="link"><inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia>
        </inertial></link>
      <model name="probe"><link name="tip"><inertial><mass>1</mass>
        <inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial></link></model>
    </model>
  </model>
  <state world_name="w"><sim_time>3 0</sim_time>
    <model name="cart"><pose>0 0 2 0 0 0</pose>
      <link name="body"><pose>0 0 2 0 0 0</pose><velocity>0 0 0 0 0 0</velocity></link>
      <model name="pod"><pose>3 4 2 0 0 0</pose>
        <link name="link"><pose>3 4 2 0 0 1.5708</pose><velocity>0.5 0 0 0 0 0</velocity></link>
        <model name="probe"><pose>5 5 5 0 0 0</pose>
          <link name="tip"><pose>5 5 5 0 0 0</pose><velocity>0 0 1 0 0 0</velocity></link></model>
      </model>
    </model>
  </state>
</world></sdf>"""


def test_nested_models_states_are_applied_to_their_scoped_links() -> None:
    """Model::SetState sets each nested model's state (its links' poses and velocities) after the model's own: the
    flattened model's links are named pod::link, pod::probe::tip (models.nested)."""
    sim = Simulation()
    warnings = sim.load_world(parse_sdf_world(NESTED))
    assert not [w for w in warnings if "nested" in w], warnings
    position, quaternion, linear, _ = sim.get_link_state("cart::pod::link")
    assert position == pytest.approx((3, 4, 2), abs=1e-9) and yaw_of(quaternion) == pytest.approx(1.5708)
    assert linear == pytest.approx((0.5, 0, 0), abs=1e-9)
    position, _, linear, _ = sim.get_link_state("cart::pod::probe::tip")
    assert position == pytest.approx((5, 5, 5), abs=1e-9) and linear == pytest.approx((0, 0, 1), abs=1e-9)
    assert sim.get_link_state("cart::body")[0] == pytest.approx((0, 0, 2), abs=1e-9)
