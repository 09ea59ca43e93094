"""The Kobuki base beyond bumpers and cliffs: wheel drops, the core sensor state's bits and motor power, without
ROS. Expected behaviour from yujinrobot/kobuki_desktop (melodic) kobuki_gazebo_plugins/src/
gazebo_ros_kobuki_updates.cpp: GazeboRosKobuki::updateWheelDrop (a wheel with no contacts has DROPPED, RAISED when it
has one again), pubSensorState (the bit flags), propagateVelocityCommands (motors off: wheel speed commands zeroed
each step); gazebo_ros_kobuki.cpp motorPowerCB. The bit values are yujinrobot/kobuki_msgs' SensorState.msg."""
from __future__ import annotations

import pytest
from conftest import TurtleSim

from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.sensors.kobuki import (
    DROPPED,
    RAISED,
    STATE_BITS_LCR,
    STATE_BITS_WHEELS,
    WHEEL_LEFT,
    WHEEL_RIGHT,
    WheelDropSensor,
    offsets_in,
    sensor_links,
    state_bits,
)
from turtle_sim_ode.world.plugins import kobuki

WHEELS = ["wheel_left_link", "wheel_right_link"]


def test_state_bits_are_kobuki_msgs():
    # SensorState: BUMPER_LEFT 4, BUMPER_CENTRE 2, BUMPER_RIGHT 1 (CLIFF_* the same); WHEEL_DROP_LEFT 2, RIGHT 1
    assert state_bits([True, False, False], STATE_BITS_LCR) == 4
    assert state_bits([False, True, False], STATE_BITS_LCR) == 2
    assert state_bits([False, False, True], STATE_BITS_LCR) == 1
    assert state_bits([True, True, True], STATE_BITS_LCR) == 7
    assert state_bits([True, False], STATE_BITS_WHEELS) == 2 and state_bits([False, True], STATE_BITS_WHEELS) == 1
    assert state_bits([], STATE_BITS_WHEELS) == 0


def test_wheels_drop_when_lifted_and_are_raised_when_back():
    sim = TurtleSim()
    sim.settle()
    drops = WheelDropSensor(sim.physics, sim.model, WHEELS)
    sim.run(0.01)
    assert drops.changes() == [] and drops.state == [False, False]
    sim.model.set_pose(0.0, 0.0, 0.2)
    sim.run(0.01)  # in the air for the whole step
    assert drops.changes() == [(WHEEL_LEFT, DROPPED), (WHEEL_RIGHT, DROPPED)]
    assert drops.state == [True, True]
    sim.run(1.0)  # falls back onto its wheels
    assert drops.changes() == [(WHEEL_LEFT, RAISED), (WHEEL_RIGHT, RAISED)]
    drops.close()
    assert drops.dropped() == []


def test_wheel_without_geoms_is_refused():
    sim = TurtleSim()
    with pytest.raises(KeyError, match="no collision geoms on wheel link 'base_footprint'"):
        WheelDropSensor(sim.physics, sim.model, ["wheel_left_link", "base_footprint"])


def test_motor_power_off_holds_the_wheels_and_drops_the_command():
    sim = TurtleSim()
    sim.settle()
    sim.run(1.0, (0.2, 0.0))
    moving = sim.pose()[0]
    assert moving > 0.1
    sim.drive.motors_enabled = False
    sim.run(0.3, (0.2, 0.0))  # commands keep coming: they are dropped
    stopped = sim.pose()[0]
    sim.run(1.0, (0.2, 0.0))
    assert sim.pose()[0] == pytest.approx(stopped, abs=0.005)
    assert sim.drive.wheel_speeds == (0.0, 0.0)
    sim.drive.motors_enabled = True
    sim.run(0.5)  # power back, no new command: still standing
    assert sim.pose()[0] == pytest.approx(stopped, abs=0.005)
    sim.run(1.0, (0.2, 0.0))
    assert sim.pose()[0] > stopped + 0.1


def test_plugin_names_its_sensors_as_gazebo_ros_kobuki_loads_reads_them():
    """GazeboRosKobuki::Load (gazebo_ros_kobuki_loads.cpp) takes the sensors by the names in these tags."""
    tags = {
        "cliff_sensor_left_name": "cl",
        "cliff_sensor_center_name": "cc",
        "cliff_sensor_right_name": "cr",
        "bumper_name": "bump",
        "imu_name": "gyro",
        "wheel_drop_left_sensor_name": "wl",
        "wheel_drop_right_sensor_name": "wr",
    }
    config = kobuki.read("mobile_base", GazeboPlugin(kobuki.KOBUKI, "kobuki_controller", tags), {})
    assert config.cliff_sensors == ("cl", "cc", "cr") and config.bumper_sensor == "bump"
    assert config.imu_sensor == "gyro" and config.wheel_drop_sensors == ("wl", "wr")
    defaults = kobuki.read("mobile_base", GazeboPlugin(kobuki.KOBUKI, "kobuki_controller", {}), {})
    # kobuki_description's kobuki_gazebo.urdf.xacro names
    assert defaults.cliff_sensors == ("cliff_sensor_left", "cliff_sensor_front", "cliff_sensor_right")
    assert (defaults.bumper_sensor, defaults.imu_sensor) == ("bumpers", "imu")
    assert defaults.wheel_drop_sensors == ("wheel_drop_left", "wheel_drop_right")


def test_sensor_links_and_their_offsets_on_the_base():
    sim = TurtleSim()
    assert sensor_links(sim.model.robot, "ray") == {"laser": "base_scan"}  # the simulator's TurtleBot
    assert sensor_links(sim.model.robot, "contact") == {}
    left, right = offsets_in(sim.model, "base_link", WHEELS)
    assert left == pytest.approx((0.0, 0.115, 0.0248), abs=1e-6)
    assert right == pytest.approx((0.0, -0.115, 0.0248), abs=1e-6)
