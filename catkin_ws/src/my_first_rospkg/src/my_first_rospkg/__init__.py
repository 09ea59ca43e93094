"""TurtleBot exercises: ROS-free cores (motion, scan) and their rospy interfaces (nodes)."""
