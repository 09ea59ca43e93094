"""Our libode 0.16 constants, checked against the header and against a real motor."""
import re
from pathlib import Path

import ode
import pytest

from turtle_sim_ode.physics import ode_constants as oc

COMMON_H = Path("/usr/include/ode/common.h")
PARAM_NAMES = [
    "LoStop",
    "HiStop",
    "Vel",
    "LoVel",
    "HiVel",
    "FMax",
    "FudgeFactor",
    "Bounce",
    "CFM",
    "StopERP",
    "StopCFM",
    "SuspensionERP",
    "SuspensionCFM",
    "ERP",
]
OUR_NAMES = [
    "PARAM_LO_STOP",
    "PARAM_HI_STOP",
    "PARAM_VEL",
    "PARAM_LO_VEL",
    "PARAM_HI_VEL",
    "PARAM_FMAX",
    "PARAM_FUDGE_FACTOR",
    "PARAM_BOUNCE",
    "PARAM_CFM",
    "PARAM_STOP_ERP",
    "PARAM_STOP_CFM",
    "PARAM_SUSPENSION_ERP",
    "PARAM_SUSPENSION_CFM",
    "PARAM_ERP",
]


@pytest.mark.skipif(not COMMON_H.exists(), reason="libode-dev headers not installed")
def test_param_order_matches_libode_header():
    macro = COMMON_H.read_text().split("#define D_ALL_PARAM_NAMES(start)")[1].split("\n\n")[0]
    header_order = re.findall(r"dParam(\w+?)\b", macro)
    assert header_order[: len(PARAM_NAMES)] == PARAM_NAMES
    assert [getattr(oc, name) for name in OUR_NAMES] == list(range(len(PARAM_NAMES)))
    assert "dParamGroup=0x100" in COMMON_H.read_text().replace(" ", "")
    assert oc.PARAM_GROUP2 + oc.PARAM_FMAX == 0x105


def _spun_wheel(fmax_param: int) -> float:
    """Hinge speed after 0.1 s of a 10 rad/s motor set up with ``fmax_param``."""
    world = ode.World()
    wheel = ode.Body(world)
    mass = ode.Mass()
    mass.setCylinderTotal(0.1, 2, 0.035, 0.02)
    wheel.setMass(mass)
    hinge = ode.HingeJoint(world)
    hinge.attach(wheel, None)
    hinge.setAnchor((0.0, 0.0, 0.0))
    hinge.setAxis((0.0, 1.0, 0.0))
    hinge.setParam(oc.PARAM_VEL, 10.0)
    hinge.setParam(fmax_param, 1.0)
    for _ in range(100):
        world.step(0.001)
    return hinge.getAngleRate()


def test_motor_turns_wheel_with_our_fmax():
    assert _spun_wheel(oc.PARAM_FMAX) == pytest.approx(10.0, rel=1e-3)


@pytest.mark.skipif(ode.ParamFMax == oc.PARAM_FMAX, reason="this PyODE's constant is not stale")
def test_pyode_stale_fmax_leaves_motor_without_force():
    assert abs(_spun_wheel(ode.ParamFMax)) < 1e-9
