"""The ROS interface: the simulator node, Gazebo's services and topics, plugin topics, the spawn_model client.

The only subpackage that imports rospy, genpy or message modules."""
