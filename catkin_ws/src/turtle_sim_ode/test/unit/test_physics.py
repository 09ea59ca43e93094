"""PhysicsParams validation, the clock, collision filtering and contact surfaces."""
import math

import ode
import pytest

from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.physics.settings import PhysicsParams
from turtle_sim_ode.physics.surfaces import SurfaceParams, combine_surfaces
from turtle_sim_ode.physics.world import PhysicsWorld


@pytest.mark.parametrize(
    "field, value",
    [
        ("time_step", 0.0),
        ("time_step", -0.001),
        ("time_step", math.nan),
        ("time_step", 1.0),
        ("solver", "dantzig"),
        ("solver_iterations", 0),
        ("solver_iterations", 1001),
        ("solver_iterations", 2.5),
        ("gravity", (0.0, 0.0, math.nan)),
        ("gravity", (0.0, 9.81)),
        ("gravity", (0.0, 0.0, -1e4)),
        ("erp", 1.5),
        ("cfm", -1.0),
        ("max_contacts", 0),
        ("contact_surface_layer", math.inf),
        ("default_surface", SurfaceParams(mu=-1.0)),
        ("ground_surface", SurfaceParams(kp=0.0)),
    ],
)
def test_validate_names_bad_field_and_value(field, value):
    params = PhysicsParams(**{field: value})
    with pytest.raises(ValueError) as error:
        params.validate()
    assert field in str(error.value)
    if not isinstance(value, SurfaceParams):
        assert repr(value) in str(error.value)
    with pytest.raises(ValueError):
        PhysicsWorld(params)


def test_defaults_are_valid():
    PhysicsParams().validate()


def test_step_advances_fixed_time_and_reset():
    physics = PhysicsWorld(PhysicsParams(time_step=0.002))
    for _ in range(3):
        physics.step()
    assert physics.sim_time == pytest.approx(0.006, abs=1e-15)
    physics.reset_time()
    assert physics.sim_time == 0.0


def _ball(physics, space, position, radius=0.1, surface=None):
    body = ode.Body(physics.world)
    mass = ode.Mass()
    mass.setSphereTotal(1.0, radius)
    body.setMass(mass)
    body.setPosition(position)
    geom = ode.GeomSphere(space, radius)
    geom.setBody(body)
    physics.register_geom(geom, surface)
    return body, geom


def test_ball_rests_on_ground():
    physics = PhysicsWorld()
    space = physics.create_model_space()
    body, _ = _ball(physics, space, (0.0, 0.0, 0.5))
    for _ in range(1500):
        physics.step()
    assert body.getPosition()[2] == pytest.approx(0.1, abs=1e-3)
    assert physics.contact_count == 1


def test_self_collision_skips_same_body_and_jointed_bodies():
    physics = PhysicsWorld(PhysicsParams(gravity=(0.0, 0.0, 0.0)))
    space = physics.create_model_space(self_collide=True)
    body_a, _ = _ball(physics, space, (0.0, 0.0, 1.0))
    body_b, _ = _ball(physics, space, (0.15, 0.0, 1.0))
    extra = ode.GeomSphere(space, 0.1)  # second geom on body_a, overlapping the first
    extra.setBody(body_a)
    physics.register_geom(extra)
    physics.step()
    assert physics.contact_count > 0  # a-b pairs only: same-body pair gives none
    contacts_ab = physics.contact_count
    physics.exclude_collision(body_a, body_b)
    physics.step()
    assert physics.contact_count == 0 < contacts_ab


def test_models_do_not_self_collide_by_default_but_collide_with_each_other():
    physics = PhysicsWorld(PhysicsParams(gravity=(0.0, 0.0, 0.0)))
    space = physics.create_model_space()
    _ball(physics, space, (0.0, 0.0, 1.0))
    _ball(physics, space, (0.15, 0.0, 1.0))
    physics.step()
    assert physics.contact_count == 0
    _ball(physics, physics.create_model_space(), (0.0, 0.15, 1.0))
    physics.step()
    assert physics.contact_count > 0


def test_ball_lands_on_static_box():
    physics = PhysicsWorld()
    table = ode.GeomBox(physics.static_space, (1.0, 1.0, 0.5))
    table.setPosition((0.0, 0.0, 0.25))
    physics.register_geom(table)
    body, _ = _ball(physics, physics.create_model_space(), (0.0, 0.0, 1.0))
    for _ in range(1500):
        physics.step()
    assert body.getPosition()[2] == pytest.approx(0.6, abs=1e-3)


def test_surfaces_combine_like_gazebo():
    a, b = SurfaceParams(mu=0.2, mu2=3.0, kp=1e6, kd=10.0), SurfaceParams(mu=1.0, mu2=0.5, kp=1e6, kd=5.0)
    _, side, adjust, mu, mu2, erp, cfm = combine_surfaces(a, b, 0.001)[:7]
    kp, kd = 5e5, 15.0  # springs in series, dampers in parallel
    assert (mu, mu2) == (0.2, 0.5)
    assert erp == pytest.approx(0.001 * kp / (0.001 * kp + kd))
    assert cfm == pytest.approx(1.0 / (0.001 * kp + kd))
    assert (side, adjust) == (0, 0)  # no fdir1, no min_depth or max_vel: the world's own contact handling


def test_gazebo_per_link_contact_parameters_combine_as_gazebos_ode():
    """Slip and min_depth the smaller; max_vel the smaller, at most the world's; fdir1 of the smaller mu1."""
    wheel = SurfaceParams(mu=0.1, mu2=0.1, kp=5e5, kd=10.0, min_depth=0.001, max_vel=0.1, fdir1=(1.0, 0.0, 0.0))
    caster = SurfaceParams(mu=0.1, kp=1e6, kd=100.0, min_depth=0.002, max_vel=1.0, slip1=0.2, slip2=0.3)
    plain = SurfaceParams(mu=0.05, fdir1=(0.0, 1.0, 0.0), slip1=0.5, slip2=0.1)
    surface = combine_surfaces(wheel, caster, 0.001, surface_layer=0.01, max_correcting_vel=2000.0)
    mode, side, adjust, _, _, erp, _, slip1, slip2, min_depth, depth_cap, layer = surface[:12]
    assert (side, surface[12:]) == (1, (1.0, 0.0, 0.0))
    assert adjust == 1 and min_depth == 0.001 and layer == 0.01
    assert depth_cap == pytest.approx(0.1 * 0.001 / erp)  # push-out (erp / dt) * depth capped at 0.1 m/s
    assert (slip1, slip2) == (0.0, 0.0) and not mode & (oc.CONTACT_SLIP1 | oc.CONTACT_SLIP2)
    surface = combine_surfaces(caster, plain, 0.001, surface_layer=0.01, max_correcting_vel=0.5)
    mode, side, _, _, _, erp, _, slip1, slip2, min_depth, depth_cap = surface[:11]
    assert (slip1, slip2) == (0.2, 0.1) and mode & oc.CONTACT_SLIP1 and mode & oc.CONTACT_SLIP2
    assert (side, surface[12:]) == (2, (0.0, 1.0, 0.0))  # plain's mu1 is the smaller
    assert min_depth == 0.002 and depth_cap == math.inf  # the world's 0.5 is lower: ODE's own cap does it
    # Neither sets them: the world's surface layer, and no cap beyond ODE's own.
    assert combine_surfaces(plain, plain, 0.001, 0.01, 2000.0)[2] == 0
    assert combine_surfaces(wheel, plain, 0.001, 0.01, 0.05)[10] == math.inf


@pytest.mark.parametrize(
    "field, value",
    [
        ("min_depth", -0.001),
        ("max_vel", -1.0),
        ("slip1", float("nan")),
        ("slip2", -0.1),
        ("fdir1", (0.0, float("inf"), 0.0)),
    ],
)
def test_bad_surface_values_are_refused(field, value):
    with pytest.raises(ValueError, match=field):
        SurfaceParams(**{field: value}).validate()


@pytest.mark.parametrize("mu", [0.3, 0.8])
def test_sliding_box_stops_where_coulomb_friction_says(mu):
    physics = PhysicsWorld(PhysicsParams(ground_surface=SurfaceParams(mu=100.0, mu2=100.0)))
    body = ode.Body(physics.world)
    mass = ode.Mass()
    mass.setBoxTotal(1.0, 0.2, 0.2, 0.1)
    body.setMass(mass)
    body.setPosition((0.0, 0.0, 0.05))
    geom = ode.GeomBox(physics.create_model_space(), (0.2, 0.2, 0.1))
    geom.setBody(body)
    physics.register_geom(geom, SurfaceParams(mu=mu, mu2=mu, kp=1e6, kd=100.0))
    for _ in range(100):
        physics.step()
    body.setLinearVel((1.0, 0.0, 0.0))
    for _ in range(1000):
        physics.step()
    assert body.getPosition()[0] == pytest.approx(1.0 / (2 * mu * 9.81), rel=0.05)


def test_lying_cylinder_line_contact_becomes_one_contact_at_its_middle():
    physics = PhysicsWorld()
    body = ode.Body(physics.world)
    mass = ode.Mass()
    mass.setCylinderTotal(1.0, 3, 0.05, 0.2)
    body.setMass(mass)
    body.setPosition((0.0, 0.0, 0.05))
    body.setQuaternion((math.cos(math.pi / 4), math.sin(math.pi / 4), 0.0, 0.0))  # axis along y
    geom = ode.GeomCylinder(physics.create_model_space(), 0.05, 0.2)
    geom.setBody(body)
    physics.register_geom(geom)
    for _ in range(1000):
        physics.step()
    assert physics.contact_count == 1
    # It still lies level where it was put: the single contact is under its middle.
    axis = body.vectorToWorld((0.0, 0.0, 1.0))
    assert abs(axis[2]) < 1e-3
    assert body.getPosition()[2] == pytest.approx(0.05, abs=1e-3)
    assert math.hypot(*body.getPosition()[:2]) < 1e-4


def test_post_step_hook_runs_after_each_step():
    physics = PhysicsWorld()
    times = []
    hook = lambda: times.append(physics.sim_time)  # noqa: E731
    physics.add_post_step_hook(hook)
    physics.step()
    physics.step()
    physics.remove_post_step_hook(hook)
    physics.step()
    assert times == [pytest.approx(0.001), pytest.approx(0.002)]
