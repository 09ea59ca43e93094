"""ROS-free helpers for demos and tests: circle fit, trajectory plot, X window dumps."""
