"""Reads the nested camera parameters that params.launch loads from config/cameras.yaml; a missing or
mistyped parameter is a fatal start-up error that names it."""
import rospy

from beginner_tutorials.params import read_param


def param_demo() -> None:
    rospy.init_node("param_demo")
    for side in ("left", "right"):
        name = read_param("~cameras/%s/name" % side, expected=str)
        exposure = read_param("~cameras/%s/exposure" % side, expected=(int, float))
        rospy.loginfo("%s camera: name [%s], exposure [%g]", side, name, exposure)
    rospy.spin()
