"""Frames as gazebo_plugins' GazeboRos gives them (issue 14): the tf_prefix parameter searched up from the plugin's
namespace, else the namespace; tf::resolve; and the frame_id of the joint states."""
from __future__ import annotations

import types

import pytest
from sensor_msgs.msg import JointState

from turtle_sim_ode.ros import plugin_topics
from turtle_sim_ode.ros import wire as ros_wire


@pytest.mark.parametrize(
    "params, namespace, expected",
    [
        ({}, "", ""),
        ({}, "/", ""),
        ({}, "robot1/", "robot1"),
        ({"/robot1/tf_prefix": "tb3_0"}, "/robot1", "tb3_0"),
        ({"/tf_prefix": "fleet"}, "/robot1/arm", "fleet"),
        ({"/robot1/tf_prefix": "near", "/tf_prefix": "far"}, "/robot1/arm/", "near"),
    ],
)
def test_tf_prefix_is_searched_up_from_the_namespace(monkeypatch, params, namespace, expected):
    monkeypatch.setattr(plugin_topics.rospy, "has_param", lambda key: key in params)
    monkeypatch.setattr(plugin_topics.rospy, "get_param", lambda key: params[key])
    assert plugin_topics.tf_prefix(namespace) == expected


@pytest.mark.parametrize(
    "prefix, frame, expected",
    [("", "odom", "odom"), ("tb3_0", "odom", "tb3_0/odom"), ("/tb3_0", "odom", "tb3_0/odom"), ("x", "/map", "map")],
)
def test_frames_resolve_as_tf_resolve(prefix, frame, expected):
    assert plugin_topics.resolve_frame(prefix, frame) == expected


def test_diff_drive_covariances_are_gazebo_ros_diff_drives():
    diagonal = [plugin_topics.DIFF_DRIVE_POSE_COVARIANCE[7 * i] for i in range(6)]
    assert diagonal == [1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3]
    assert sum(plugin_topics.DIFF_DRIVE_POSE_COVARIANCE) == sum(diagonal)
    assert plugin_topics.DIFF_DRIVE_TWIST_COVARIANCE == (0.0,) * 36


def test_joint_states_carry_their_frame_id():
    packed = ros_wire.JointStatePacker(["a", "b"], "tb3_0/base_link").pack(3, 4, 5, (1.0, 2.0), (3.0, 4.0))
    message = JointState()
    message.deserialize(packed)
    assert (message.header.frame_id, message.name, list(message.position)) == ("tb3_0/base_link", ["a", "b"], [1, 2])


@pytest.mark.parametrize(
    "params, namespace, expected",
    [
        ({}, "/robot1", ""),
        ({"/robot1/tf_prefix": "tb3_0"}, "/robot1", "tb3_0"),
        ({"/robot1/tf_prefix": "tb3_0"}, "robot1/", "tb3_0"),
        ({"/tf_prefix": "fleet"}, "/robot1", ""),  # not searched upwards
        ({"/tf_prefix": "fleet"}, "", "fleet"),
    ],
)
def test_p3d_and_bumper_read_their_own_namespaces_tf_prefix(monkeypatch, params, namespace, expected):
    """gazebo_ros_p3d.cpp and gazebo_ros_bumper.cpp, Load: ros::NodeHandle(robotNamespace).getParam("tf_prefix")."""
    monkeypatch.setattr(plugin_topics.rospy, "get_param", lambda key, default: params.get(key, default))
    assert plugin_topics.own_tf_prefix(namespace) == expected


class Capture:
    """A publisher of either kind (packed or genpy) that keeps what is published, as genpy messages."""

    def __init__(self, topic, data_class, *args, **kwargs):
        self.data_class, self.messages = data_class, []
        self.impl = types.SimpleNamespace(connections=[object()])  # one subscriber, as wire.heard reads it

    def heard(self):
        return True

    def publish(self, message, *fields):
        if fields:  # packed: a pack function and its fields
            packed, message = message(1, *fields), self.data_class()
            message.deserialize(ros_wire.joined(packed))
        self.messages.append(message)

    def unregister(self):
        pass


P3D_AND_BUMPER = """<robot name="bot">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <gazebo><plugin name="truth" filename="libgazebo_ros_p3d.so"><bodyName>base</bodyName>
    <topicName>truth</topicName><frameName>{p3d_frame}</frameName></plugin></gazebo>
  <gazebo reference="base"><sensor name="bumper" type="contact"><contact><collision>base_collision</collision>
    </contact><plugin name="b" filename="libgazebo_ros_bumper.so"><bumperTopicName>bumps</bumperTopicName>
    <frameName>{bumper_frame}</frameName></plugin></sensor></gazebo>
</robot>"""


@pytest.mark.parametrize(
    "p3d_frame, bumper_frame, expected_p3d, expected_bumper",
    [
        ("world", "base", "tb3_0/world", "tb3_0/base"),  # gazebo_ros_p3d: tf::resolve(prefix, frameName)
        ("/map", "/base", "map", "base"),  # a leading slash: the frame as it is (tf::resolve)
    ],
)
def test_p3d_and_bumper_frames_take_the_namespaces_tf_prefix(
    monkeypatch, p3d_frame, bumper_frame, expected_p3d, expected_bumper
):
    from nav_msgs.msg import Odometry  # noqa: F401 (the p3d's type, deserialised by Capture)

    from turtle_sim_ode.ros import periodic
    from turtle_sim_ode.ros.plugins import model_interfaces
    from turtle_sim_ode.ros.settings import SimulatorSettings
    from turtle_sim_ode.world.simulation import Simulation

    monkeypatch.setattr(periodic, "PackedPublisher", Capture)
    monkeypatch.setattr(periodic.rospy, "Publisher", Capture)
    params = {"/ns/tf_prefix": "tb3_0"}
    monkeypatch.setattr(plugin_topics.rospy, "get_param", lambda key, default=None: params.get(key, default))
    sim = Simulation()
    sim.spawn_urdf("bot", P3D_AND_BUMPER.format(p3d_frame=p3d_frame, bumper_frame=bumper_frame), (0, 0, 0.1, 0, 0, 0))
    interfaces = model_interfaces("bot", sim, SimulatorSettings(), None, "/ns", lambda topic, kind: None)
    frames = {}
    for interface in interfaces:
        interface.publish(plugin_topics.rospy.Time(1, 0), 1.0)
        for capture in [value for value in vars(interface).values() if isinstance(value, Capture)]:
            frames[capture.data_class.__name__] = capture.messages[0].header.frame_id
    assert frames == {"Odometry": expected_p3d, "ContactsState": expected_bumper}
