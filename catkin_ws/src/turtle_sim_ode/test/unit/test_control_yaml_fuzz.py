"""Generated controller configurations (Hypothesis): whatever a YAML file puts under a controller's name, load
answers True or False with an error naming the reason, never raises; a controller that loaded runs, and the
manager's invariants hold after every call (no joint claimed twice by running controllers, states known)."""
from __future__ import annotations

from control_helpers import ARM_URDF, BASE_URDF, Rig
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from turtle_sim_ode.control.manager import CONTROLLER_TYPES

JOINTS = ["shoulder", "elbow", "front_left_wheel", "rear_right_wheel", "wrist", ""]
scalars = st.one_of(
    st.none(), st.booleans(), st.integers(-5, 5), st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=6)
)
joint_names = st.sampled_from(JOINTS)
values = st.recursive(
    st.one_of(scalars, joint_names),
    lambda inner: st.one_of(st.lists(inner, max_size=4), st.dictionaries(st.sampled_from(["p", "i", "d", "x"]), inner)),
    max_leaves=8,
)
KEYS = [
    "joint",
    "joints",
    "pid",
    "gains",
    "publish_rate",
    "left_wheel",
    "right_wheel",
    "wheel_radius",
    "wheel_separation",
    "constraints",
    "cmd_vel_timeout",
    "pose_covariance_diagonal",
    "linear",
    "extra_joints",
]
MISSING = object()
OPTIONAL = {
    "joint": joint_names,
    "joints": st.one_of(st.lists(joint_names, max_size=3), values),
    "pid": st.one_of(st.fixed_dictionaries({"p": st.floats(-10, 10)}), values),
    "gains": values,
    "publish_rate": st.one_of(st.floats(0.1, 100), values),
    "left_wheel": st.one_of(joint_names, st.lists(joint_names, max_size=2), values),
    "right_wheel": st.one_of(joint_names, st.lists(joint_names, max_size=2), values),
    **{key: values for key in KEYS[7:]},
}
# fixed_dictionaries' optional= is newer than Ubuntu 20.04's Hypothesis: absent keys are drawn as MISSING and dropped
configs = st.fixed_dictionaries(
    dict(
        {"type": st.one_of(st.sampled_from(sorted(CONTROLLER_TYPES)), st.text(max_size=12), st.integers())},
        **{key: st.one_of(st.just(MISSING), strategy) for key, strategy in OPTIONAL.items()},
    )
).map(lambda drawn: {key: value for key, value in drawn.items() if value is not MISSING})


def check_invariants(rig: Rig) -> None:
    running = [entry for entry in rig.manager.loaded if entry.state == "running"]
    claimed = [joint for entry in running for joint in entry.controller.claimed]
    assert len(claimed) == len(set(claimed))
    assert all(entry.state in ("initialized", "running", "stopped") for entry in rig.manager.loaded)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(urdf=st.sampled_from([ARM_URDF, BASE_URDF]), config_list=st.lists(configs, min_size=1, max_size=4))
def test_generated_configurations_load_or_refuse_clearly(urdf, config_list):
    rig = Rig(urdf)
    for index, config in enumerate(config_list):
        name = f"c{index}"
        errors_before = len(rig.errors())
        if rig.manager.load(name, config):
            rig.manager.switch([name], [], 1)
        else:
            assert len(rig.errors()) > errors_before and all(rig.errors()[errors_before:])
        check_invariants(rig)
        rig.run(0.005)
        check_invariants(rig)
