"""talker and listener on chatter (the "Writing a Simple Publisher and Subscriber (Python)" tutorial)."""
import rospy
from std_msgs.msg import String

from beginner_tutorials.params import read_param, read_rate


def talker() -> None:
    rospy.init_node("talker")
    rate_hz = read_rate("~rate", 10.0)
    prefix = read_param("~message", "hello world", str)
    pub = rospy.Publisher("chatter", String, queue_size=1000)
    rate = rospy.Rate(rate_hz)
    count = 0
    while not rospy.is_shutdown():
        text = "%s %d" % (prefix, count)
        rospy.loginfo(text)
        pub.publish(text)
        count += 1
        rate.sleep()


def listener() -> None:
    rospy.init_node("listener")
    rospy.Subscriber("chatter", String, lambda msg: rospy.loginfo("I heard: [%s]", msg.data), queue_size=1000)
    rospy.spin()
