"""Planar paths of Odometry topics in a rosbag, for plot_trajectory.py."""
from typing import Dict, List, Sequence, Tuple

import rosbag


def read_paths(bag_file: str, topics: Sequence[str]) -> Dict[str, List[Tuple[float, float]]]:
    """(x, y) of every Odometry message of each topic, in bag order; a topic missing from the bag gives []."""
    paths: Dict[str, List[Tuple[float, float]]] = {topic: [] for topic in topics}
    with rosbag.Bag(bag_file) as bag:
        for topic, msg, _ in bag.read_messages(topics=list(topics)):
            paths[topic].append((msg.pose.pose.position.x, msg.pose.pose.position.y))
    return paths
