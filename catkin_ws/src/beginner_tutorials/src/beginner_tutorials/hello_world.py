"""The ETH course's first node: a rospy.Rate loop that logs, plus one message at each severity."""
import rospy

from beginner_tutorials.params import read_param, read_rate


def hello_world() -> None:
    rospy.init_node("hello_world")
    rate_hz = read_rate("~rate", 10.0)
    count_limit = read_param("~count", 0, int)  # 0 = run until shut down

    rospy.logdebug("DEBUG: shown only when the logger level is debug")
    rospy.loginfo("INFO: normal operation")
    rospy.logwarn("WARN: something unexpected that the node can live with")
    rospy.logerr("ERROR: something failed, the node goes on")
    rospy.logfatal("FATAL: an example only, this node keeps running")

    rate = rospy.Rate(rate_hz)
    count = 0
    while not rospy.is_shutdown() and (count_limit <= 0 or count < count_limit):
        rospy.loginfo("Hello World %d", count)
        count += 1
        rate.sleep()
