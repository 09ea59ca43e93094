"""ROS-free helpers for demos, tests and the scripts: circle fit, trajectory plot, waiting on the wall clock."""
