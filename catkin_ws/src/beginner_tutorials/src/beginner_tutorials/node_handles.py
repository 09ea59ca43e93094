"""How a topic name resolves as relative, private (~), namespaced and global name: the rospy counterpart of
the roscpp node-handle demo. Run it in a namespace (ROS_NAMESPACE=demo or <group ns="demo">)."""
import rospy
from std_msgs.msg import String

# rospy has no node handles: the same four cases are spelt in the name itself.
NAMES = (
    ('default    "chatter"', "chatter"),
    ('private    "~chatter"', "~chatter"),
    ('namespaced "sub/chatter"', "sub/chatter"),
    ('global     "/chatter"', "/chatter"),
)


def node_handles() -> None:
    rospy.init_node("node_handles")
    publishers = []
    for label, name in NAMES:
        rospy.loginfo("%s -> %s", label, rospy.resolve_name(name))
        publishers.append(rospy.Publisher(name, String, queue_size=1, latch=True))
    for publisher in publishers:
        publisher.publish("published on " + publisher.resolved_name)
    rospy.spin()
