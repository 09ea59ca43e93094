"""pointcloud_to_laserscan's node as a drop-in: a ROS-free core (``scan``) and its ROS interface (``node``)."""
