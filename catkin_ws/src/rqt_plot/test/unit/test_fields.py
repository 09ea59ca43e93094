"""Which names the Topic box completes and which curves a name gives. Expected values from rqt_plot (noetic)
src/rqt_plot/plot_widget.py, get_plot_fields: a message gives its numeric non-array fields, a fixed-size numeric
array one curve per element, a variable-size one none; and from the message definitions (turtlesim/Pose:
x y theta linear_velocity angular_velocity, all float32)."""
import pytest
import roslib.message
from geometry_msgs.msg import PoseStamped

from rqt_plot.fields import FieldReader, completions, parse_slot_type, plot_fields

POSE_FIELDS = ["x", "y", "theta", "linear_velocity", "angular_velocity"]


class TurtlePose:
    """turtlesim/Pose's class as genpy makes it (the workspace's turtlesim may not be built here)."""

    __slots__ = POSE_FIELDS
    _slot_types = ["float32"] * 5


def load(type_name):
    return TurtlePose if type_name == "turtlesim/Pose" else roslib.message.get_message_class(type_name)


TOPICS = {
    "/turtle1/pose": "turtlesim/Pose",
    "/turtle1/cmd_vel": "geometry_msgs/Twist",
    "/odom_pose": "geometry_msgs/PoseWithCovariance",
    "/ranges": "std_msgs/Float32MultiArray",
    "/rosout": "rosgraph_msgs/Log",
}


def test_slot_types():
    assert parse_slot_type("float64[36]") == ("float64", True, 36)
    assert parse_slot_type("uint8[]") == ("uint8", True, None)
    assert parse_slot_type("geometry_msgs/Point") == ("geometry_msgs/Point", False, None)


def test_turtle_pose_completes_to_its_five_fields():
    assert completions("/turtle1/pose", "turtlesim/Pose", load) == ["/turtle1/pose"] + [
        "/turtle1/pose/" + field for field in POSE_FIELDS
    ]


def test_nested_messages_and_fixed_arrays_complete_by_index():
    names = completions("/odom_pose", "geometry_msgs/PoseWithCovariance", load)
    assert "/odom_pose/pose" in names and "/odom_pose/pose/position/x" in names
    assert "/odom_pose/pose/orientation/w" in names
    assert ["/odom_pose/covariance[%d]" % i for i in range(36)] == [n for n in names if "covariance" in n]
    stamped = completions("/goal", "geometry_msgs/PoseStamped", load)
    assert "/goal/header/stamp/secs" in stamped and "/goal/header/seq" in stamped
    assert "/goal/header/frame_id" not in stamped  # a string


def test_a_message_gives_its_numeric_fields():
    assert plot_fields("/turtle1/pose", TOPICS, load)[0] == ["/turtle1/pose/" + f for f in POSE_FIELDS]
    assert plot_fields("/turtle1/cmd_vel/linear", TOPICS, load)[0] == [
        "/turtle1/cmd_vel/linear/" + axis for axis in "xyz"
    ]


def test_a_numeric_field_gives_itself():
    assert plot_fields("/turtle1/pose/x", TOPICS, load) == (["/turtle1/pose/x"], "/turtle1/pose/x is numeric")


def test_arrays():
    assert plot_fields("/odom_pose/covariance", TOPICS, load)[0] == ["/odom_pose/covariance[%d]" % i for i in range(36)]
    curves, why = plot_fields("/ranges/data", TOPICS, load)
    assert curves == [] and "variable-size" in why
    assert plot_fields("/ranges/data[3]", TOPICS, load)[0] == ["/ranges/data[3]"]
    assert plot_fields("/odom_pose/covariance[36]", TOPICS, load)[0] == []


@pytest.mark.parametrize(
    "path",
    ["/nothing/x", "/turtle1/pose/z", "/turtle1/pose/x[0]", "/rosout/msg", "/turtle1/pose/x/y", "/turtle1/pose/$"],
)
def test_what_cannot_be_plotted_gives_nothing_and_says_why(path):
    curves, why = plot_fields(path, TOPICS, load)
    assert curves == [] and why


def test_reader_follows_fields_and_indices():
    message = PoseStamped()
    message.pose.position.y = 2.5
    assert FieldReader("pose/position/y")(message) == 2.5

    class Ranges:
        data = [1.0, 2.0, 3.0]

    assert FieldReader("data[2]")(Ranges()) == 3.0
    with pytest.raises(IndexError):
        FieldReader("data[5]")(Ranges())
    with pytest.raises(ValueError):
        FieldReader("data[x]")
