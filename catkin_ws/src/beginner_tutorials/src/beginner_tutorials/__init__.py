"""Python side of the ROS beginner tutorials: each node here has a C++ twin with the same API."""
