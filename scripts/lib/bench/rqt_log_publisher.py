#!/usr/bin/env python3
"""The console benchmark's log source (scripts/bench_rqt.py): rosgraph_msgs/Log on /rosout_agg at a given rate,
in 10 ms batches, once a subscriber is connected; prints `sent N` at the end. Severities cycle through the five
levels so that every colour is drawn.

  rqt_log_publisher.py --rate 1000 --seconds 30
"""
import argparse
import time

import rospy
from rosgraph_msgs.msg import Log

LEVELS = (Log.DEBUG, Log.INFO, Log.WARN, Log.ERROR, Log.FATAL)
BATCH_PERIOD_S = 0.01


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rate", type=float, default=1000.0, help="messages per second")
    parser.add_argument("--seconds", type=float, default=30.0, help="how long to publish")
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("bench_log_source")
    publisher = rospy.Publisher("/rosout_agg", Log, queue_size=10000)
    while publisher.get_num_connections() == 0 and not rospy.is_shutdown():
        time.sleep(0.05)  # the console's subscription: nothing else to wait on
    sent, start = 0, time.monotonic()
    total = int(args.rate * args.seconds)
    while sent < total and not rospy.is_shutdown():
        due = min(total, int((time.monotonic() - start) * args.rate) + 1)
        while sent < due:
            log = Log(level=LEVELS[sent % len(LEVELS)], name="/bench_log_source", msg="bench message %d" % sent)
            log.header.stamp = rospy.Time.now()
            log.file, log.function, log.line, log.topics = "rqt_log_publisher.py", "main", 40, ["/rosout_agg"]
            publisher.publish(log)
            sent += 1
        time.sleep(BATCH_PERIOD_S)
    time.sleep(1.0)  # let the last batch leave the socket before the node goes
    print("sent %d in %.3f s" % (sent, time.monotonic() - start), flush=True)


if __name__ == "__main__":
    main()
