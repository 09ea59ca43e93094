"""fdir1 reaches ODE as Gazebo hands it (issue #31): turned by its geom's rotation, neither projected onto the
contact plane nor normalised.

Expected values from gazebo-classic's sources:
- gazebo/physics/ode/ODEPhysics.cc, ODEPhysics::Collide: "fdir1 is in body local frame, rotate it into world
  frame" (``RotateVector`` of the collision's world rotation, nothing else), then ``contact.fdir1 = fd`` with
  ``dContactFDir1``.
- deps/opende/src/joints/contact.cpp, dxJointContact::getInfo2: t1 = fdir1, t2 = normal x t1 (both as they are);
  only where t2 vanishes (fdir1 along the normal) ``dPlaneSpace(normal, t1, t2)``, which stock ODE uses without
  dContactFDir1.
So a wheel's ``<fdir1>1 0 0</fdir1>`` (smb_description, turtlebot3_description) turns with the wheel: at a wheel
angle a its friction rows are (cos a, 0, sin a) and (0, cos a, 0) in the wheel's frame of travel, not the unit
forward and sideways directions."""
from __future__ import annotations

import math

from hypothesis import given
from hypothesis import strategies as st

from turtle_sim_ode.physics.contacts import PARALLEL_FDIR1_TOLERANCE, friction_direction

UP = (0.0, 0.0, 1.0)
IDENTITY = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)


def _wheel_rotation(angle: float):
    """A wheel as smb_description mounts it (joint rpy -pi/2 about x: its z axis sideways), turned by ``angle``
    about its axle; row-major."""
    c, s = math.cos(angle), math.sin(angle)
    # Rx(-pi/2) @ Rz(angle)
    return (c, -s, 0.0, 0.0, 0.0, 1.0, -s, -c, 0.0)


def _rotation(roll: float, pitch: float, yaw: float):
    cr, sr, cp, sp = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return (
        cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
        sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
        -sp, cp * sr, cp * cr,
    )  # fmt: skip


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def test_a_rolling_wheels_fdir1_tilts_with_the_wheel_unprojected():
    for angle in (0.0, 0.3, 1.0, 2.5, -0.7):
        direction = friction_direction(_wheel_rotation(angle), (1.0, 0.0, 0.0), UP)
        assert direction is not None
        expected = (math.cos(angle), 0.0, -math.sin(angle))
        assert all(math.isclose(d, e, abs_tol=1e-12) for d, e in zip(direction, expected))
        # the second row, normal x fdir1, shrinks with cos(angle) (ODE's dCalcVectorCross3, unnormalised)
        second = _cross(UP, direction)
        assert math.isclose(math.hypot(*second), abs(math.cos(angle)), abs_tol=1e-12)


def test_fdir1_along_the_normal_leaves_odes_own_directions():
    """The wheel's x axis pointing straight down: normal x fdir1 = 0, Gazebo's ODE falls back to dPlaneSpace."""
    assert friction_direction(_wheel_rotation(math.pi / 2), (1.0, 0.0, 0.0), UP) is None
    assert friction_direction(IDENTITY, (0.0, 0.0, 2.0), UP) is None
    assert friction_direction(IDENTITY, (0.0, 0.0, 0.0), UP) is None


def test_an_unnormalised_fdir1_is_handed_on_unnormalised():
    assert friction_direction(IDENTITY, (2.0, 0.0, 0.5), UP) == (2.0, 0.0, 0.5)


angles = st.floats(-math.pi, math.pi, allow_nan=False)
components = st.floats(-2.0, 2.0, allow_nan=False)


@given(angles, angles, angles, st.tuples(components, components, components), angles, angles)
def test_generated_fdir1_is_only_turned(roll, pitch, yaw, fdir1, normal_tilt, normal_heading):
    """Invariants: the direction has fdir1's length (a rotation, no projection or normalisation), is the turned fdir1,
    and is None exactly where normal x direction vanishes."""
    rotation = _rotation(roll, pitch, yaw)
    normal = (
        math.sin(normal_tilt) * math.cos(normal_heading),
        math.sin(normal_tilt) * math.sin(normal_heading),
        math.cos(normal_tilt),
    )
    turned = tuple(sum(rotation[3 * row + k] * fdir1[k] for k in range(3)) for row in range(3))
    direction = friction_direction(rotation, fdir1, normal)
    if all(abs(c) <= PARALLEL_FDIR1_TOLERANCE for c in _cross(normal, turned)):
        assert direction is None
        return
    assert direction is not None
    assert math.isclose(math.hypot(*direction), math.hypot(*fdir1), rel_tol=1e-9, abs_tol=1e-12)
    assert all(math.isclose(d, t, rel_tol=1e-12, abs_tol=1e-12) for d, t in zip(direction, turned))
