"""The window on a stand-in for joint_state_publisher's JointStatePublisher (its joint_list, free_joints dicts and
set_source_update_cb, as the GUI of ros/joint_state_publisher noetic-devel uses them)."""
from __future__ import annotations

import math

import pytest

from joint_state_publisher_gui.sliders import RANGE
from joint_state_publisher_gui.window import JointStatePublisherGui


class StandIn:
    """What JointStatePublisher.init_urdf makes of test/urdf/pan_tilt_cart.urdf (continuous: ±π)."""

    def __init__(self) -> None:
        self.joint_list = ["head_pan", "head_tilt", "wheel_joint", "gripper_extension", "gripper_twin_extension"]
        limits = {
            "head_pan": (-1.2, 1.5),
            "head_tilt": (0.0, 0.8),
            "wheel_joint": (-math.pi, math.pi),
            "gripper_extension": (-0.1, 0.2),
        }
        self.free_joints = {
            name: {"min": low, "max": high, "zero": 0.0, "position": 0.0} for name, (low, high) in limits.items()
        }
        self.free_joints["wheel_joint"]["continuous"] = True
        self.source_update_cb = None

    def set_source_update_cb(self, callback) -> None:
        self.source_update_cb = callback


@pytest.fixture
def gui(qtbot):
    jsp = StandIn()
    window = JointStatePublisherGui("Node: /joint_state_publisher_gui", jsp)
    qtbot.addWidget(window)
    return window


def test_a_slider_per_movable_joint_in_the_descriptions_order(gui):
    assert list(gui.sliders) == ["head_pan", "head_tilt", "wheel_joint", "gripper_extension"]  # the mimic has none
    assert gui.windowTitle() == "Node: /joint_state_publisher_gui"
    assert gui.maxrowsupdown.value() == 4 and gui.maxrowsupdown.maximum() == 4
    assert [gui.randbutton.text(), gui.ctrbutton.text()] == ["Randomize", "Center"]


def test_moving_a_slider_sets_the_joint_and_its_display(gui):
    head_tilt = gui.sliders["head_tilt"]
    head_tilt.slider.setValue(RANGE)
    assert gui.jsp.free_joints["head_tilt"]["position"] == pytest.approx(0.8)
    assert head_tilt.display.text() == "0.800"


def test_center_and_randomize(gui):
    gui.randbutton.click()
    for name, joint in gui.jsp.free_joints.items():
        assert joint["min"] - 1e-9 <= joint["position"] <= joint["max"] + 1e-9, name
    gui.ctrbutton.click()
    step = {name: (j["max"] - j["min"]) / RANGE for name, j in gui.jsp.free_joints.items()}
    for name, joint in gui.jsp.free_joints.items():
        assert abs(joint["position"] - joint["zero"]) <= step[name], name


def test_joint_states_from_sources_move_the_sliders(gui, qtbot):
    gui.jsp.free_joints["gripper_extension"]["position"] = 0.2
    gui.jsp.source_update_cb()  # joint_state_publisher calls it from its subscriber's thread
    qtbot.waitUntil(lambda: gui.sliders["gripper_extension"].slider.value() == RANGE, timeout=2000)


def test_rows(gui):
    gui.maxrowsupdown.setValue(2)
    positions = {name: gui.grid.getItemPosition(gui.grid.indexOf(s.layout))[:2] for name, s in gui.sliders.items()}
    assert positions == {"head_pan": (0, 0), "head_tilt": (1, 0), "wheel_joint": (0, 1), "gripper_extension": (1, 1)}
