#!/usr/bin/env python3
"""rostest node: node /gazebo offers exactly the topics and services of ~api (a YAML file), with their types.

Written after gazebo_ros's gazebo_ros/test/ros_network tests (noetic-devel), which compare `rostopic list` and
`rosservice list` with a list of names and types once Gazebo is up; here the master is asked what node /gazebo
itself publishes, subscribes to and serves, so that the test's own nodes and roscore's do not count.
"""
import unittest

import rosgraph
import rospy
import rosservice
import rostest
import yaml
from rosgraph_msgs.msg import Clock

NODE = "/gazebo"


class GazeboApiTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("ros_api_check")
        with open(rospy.get_param("~api")) as api_file:
            cls.api = yaml.safe_load(api_file)
        # /gazebo publishes /clock once its world is loaded and its API offered (ros.node: advertise, then run)
        rospy.wait_for_message("/clock", Clock, timeout=120)
        cls.master = rosgraph.Master(rospy.get_name())
        cls.publishes, cls.subscribes, services = cls.master.getSystemState()
        cls.services = {name for name, nodes in services if NODE in nodes}

    def node_topics(self, entries) -> set:
        return {topic for topic, nodes in entries if NODE in nodes}

    def test_published_topics(self) -> None:
        expected = {topic for topic, entry in self.api["topics"].items() if entry["publishes"]}
        self.assertEqual(self.node_topics(self.publishes), expected)

    def test_subscribed_topics(self) -> None:
        expected = {topic for topic, entry in self.api["topics"].items() if not entry["publishes"]}
        self.assertEqual(self.node_topics(self.subscribes), expected)

    def test_topic_types(self) -> None:
        types = dict(self.master.getTopicTypes())
        for topic, entry in self.api["topics"].items():
            self.assertEqual(types.get(topic), entry["type"], topic)

    def test_services(self) -> None:
        self.assertEqual(self.services, set(self.api["services"]))

    def test_service_types(self) -> None:
        for service, service_type in self.api["services"].items():
            self.assertEqual(rosservice.get_service_type(service), service_type, service)


if __name__ == "__main__":
    rostest.rosrun("gazebo_ros", "ros_api_check", GazeboApiTest)
