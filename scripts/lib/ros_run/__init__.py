"""Running ROS tools from scripts and tests: process groups, masters, /proc figures, a raw TCPROS reader, the
workspace's environment."""
