"""ROS-free physics core of the TurtleBot simulator (PyODE)."""
