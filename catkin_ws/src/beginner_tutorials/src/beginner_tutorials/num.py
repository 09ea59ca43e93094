"""Publisher and subscriber of the custom message beginner_tutorials/Num on num."""
import rospy

from beginner_tutorials.msg import Num
from beginner_tutorials.params import read_rate


def num_publisher() -> None:
    rospy.init_node("num_publisher")
    pub = rospy.Publisher("num", Num, queue_size=10)
    rate = rospy.Rate(read_rate("~rate", 10.0))
    count = 0
    while not rospy.is_shutdown():
        pub.publish(Num(num=count))
        count += 1
        rate.sleep()


def num_subscriber() -> None:
    rospy.init_node("num_subscriber")
    rospy.Subscriber("num", Num, lambda msg: rospy.loginfo("I heard: [%d]", msg.num), queue_size=10)
    rospy.spin()
