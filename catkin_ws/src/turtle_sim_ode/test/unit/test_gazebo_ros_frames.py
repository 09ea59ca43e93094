"""Frames as gazebo_plugins' GazeboRos gives them (issue 14): the tf_prefix parameter searched up from the plugin's
namespace, else the namespace; tf::resolve; and the frame_id of the joint states."""
from __future__ import annotations

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
