#!/usr/bin/env python3
"""Turn a recorded run (a rosbag with nav_msgs/Odometry, e.g. /ground_truth/odom or /odom) into a PNG of the path.

  rosrun my_first_rospkg plot_trajectory.py run.bag -o path.png [--topic /ground_truth/odom] [--title circle]
"""
import argparse
import sys

from my_first_rospkg.bag_paths import read_paths
from turtle_sim_ode.analysis.trajectory_plot import plot_paths


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bag")
    parser.add_argument("-o", "--output", required=True, help="PNG to write")
    parser.add_argument("--topic", action="append", help="Odometry topic (repeatable; default: /ground_truth/odom)")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    topics = args.topic or ["/ground_truth/odom"]
    paths = read_paths(args.bag, topics)
    if not any(paths.values()):
        print("no Odometry on %s in %s" % (", ".join(topics), args.bag), file=sys.stderr)
        return 1
    plot_paths(paths, args.output, args.title)
    print("wrote %s" % args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
