"""Issue #33: a model's IMU plugins on one link at one rate are one ImuGroup (ros.plugins.imu): the link is read once
per due time whatever the number of IMUs, only the IMUs someone listens to are noised and packed, and each of those
reads what a lone ImuSensor with its noise reads."""
from __future__ import annotations

import random
import socket

import pytest
from sensor_msgs.msg import Imu

from turtle_sim_ode.sensors.imu import ImuSensor
from turtle_sim_ode.sensors.plugins.imu import ImuNoise
from turtle_sim_ode.world.simulation import Simulation

INERTIA = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


def imus_on_one_link(count: int, rate: float = 0.0) -> str:
    sensors = "".join(
        f'<sensor type="imu" name="imu{i}"><update_rate>{rate:g}</update_rate>'
        f'<plugin name="imu{i}" filename="libgazebo_ros_imu_sensor.so"><topicName>imu{i}</topicName>'
        f"<gaussianNoise>{0.01 * (i % 2)}</gaussianNoise></plugin></sensor>"
        for i in range(count)
    )
    return (
        f'<robot name="imus"><link name="base">{INERTIA}<collision><geometry><box size="0.2 0.2 0.2"/></geometry>'
        f'</collision></link><link name="arm">{INERTIA}</link><joint name="j" type="fixed"><parent link="base"/>'
        f'<child link="arm"/></joint><gazebo reference="base">{sensors}</gazebo>'
        f'<gazebo reference="arm"><sensor type="imu" name="other"><update_rate>100</update_rate>'
        f'<plugin name="other" filename="libgazebo_ros_imu_sensor.so"><topicName>other</topicName></plugin></sensor>'
        f"</gazebo></robot>"
    )


class Subscriber:
    """What rospy's topic object and ros.wire.send use of a TCPROS connection; reads what it was sent."""

    def __init__(self, name: str) -> None:
        self.endpoint_id, self.cleanup_cb = name, None
        self.socket, self._theirs = socket.socketpair()
        self.done = False
        self.stat_bytes = self.stat_num_msg = 0

    def fileno(self) -> int:
        return self.socket.fileno()

    def set_cleanup_callback(self, callback) -> None:  # type: ignore[no-untyped-def]
        self.cleanup_cb = callback

    def messages(self) -> list:
        self._theirs.setblocking(False)
        data = b""
        while True:
            try:
                data += self._theirs.recv(1 << 16)
            except BlockingIOError:
                break
        found = []
        while data:
            size = int.from_bytes(data[:4], "little")
            found.append(Imu().deserialize(data[4 : 4 + size]))
            data = data[4 + size :]
        return found


@pytest.fixture
def groups(monkeypatch):
    import rospy

    from turtle_sim_ode.ros.plugins import imu as imu_adapter
    from turtle_sim_ode.ros.plugins import model_interfaces
    from turtle_sim_ode.ros.periodic import sim_stamp
    from turtle_sim_ode.ros.settings import SimulatorSettings

    monkeypatch.setattr(rospy, "has_param", lambda key: False)
    sim = Simulation()
    sim.spawn_urdf("imus", imus_on_one_link(300), (0, 0, 0.5, 0, 0, 0))  # falling: the acceleration is -g
    interfaces = model_interfaces("imus", sim, SimulatorSettings(), None, "")
    yield sim, interfaces, imu_adapter, sim_stamp
    for interface in interfaces:
        interface.close()


def test_imus_on_one_link_at_one_rate_are_one_group_that_reads_the_link_once(groups, monkeypatch):
    sim, interfaces, imu_adapter, sim_stamp = groups
    assert len(interfaces) == 2 and all(isinstance(i, imu_adapter.ImuGroup) for i in interfaces)  # base, arm
    reads, noised = [], []
    exact, with_noise = ImuSensor.exact, ImuSensor.with_noise
    monkeypatch.setattr(ImuSensor, "exact", lambda self, now: reads.append(now) or exact(self, now))
    monkeypatch.setattr(
        ImuSensor, "with_noise", lambda self, reading: noised.append(reading) or with_noise(self, reading)
    )
    base = next(i for i in interfaces if len(i._pubs) == 300)
    for _ in range(10):
        sim.step()
        base.publish(sim_stamp(sim.sim_time), sim.sim_time)
    assert len(reads) == 10 and noised == []  # nobody listens: one read of the link per step, nothing packed


def test_only_the_imus_someone_listens_to_are_published_each_as_a_lone_sensor_reads(groups):
    sim, interfaces, imu_adapter, sim_stamp = groups
    base = next(i for i in interfaces if len(i._pubs) == 300)
    listeners = {7: Subscriber("/a"), 8: Subscriber("/b")}
    for index, listener in listeners.items():
        base._pubs[index]._pub.impl.add_connection(listener)  # as rospy's TCPROS server does: the listeners hear of it
    model = sim.models["imus"]
    lone = {7: ImuSensor(model, "base", noise=ImuNoise(0.01, 0.01, 0.01)), 8: ImuSensor(model, "base")}  # odd: noisy
    base._sensors[7].rng, lone[7].rng = random.Random(5), random.Random(5)
    expected = {7: [], 8: []}
    for _ in range(5):
        sim.step()
        now = sim.sim_time
        base.publish(sim_stamp(now), now)
        for index, sensor in lone.items():
            expected[index].append(sensor.read(now))
    for index, listener in listeners.items():
        got = listener.messages()
        assert len(got) == 5
        for message, reading in zip(got, expected[index]):
            acceleration = message.linear_acceleration
            assert (acceleration.x, acceleration.y, acceleration.z) == pytest.approx(reading.linear_acceleration)
            assert message.orientation_covariance == pytest.approx(reading.orientation_covariance)
    assert abs(got[-1].linear_acceleration.z) < 1e-6  # IMU 8, exact, falling freely: no proper acceleration
