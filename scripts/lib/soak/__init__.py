"""The soak test of scripts/soak.py: its ROS node, the sampling run and the verdict."""
