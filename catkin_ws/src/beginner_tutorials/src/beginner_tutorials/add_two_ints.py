"""add_two_ints server and client (the "Writing a Simple Service and Client (Python)" tutorial)."""
import sys
from typing import List

import rosgraph
import rospy

from beginner_tutorials.checked_int import MAX_TIMEOUT, checked_add, parse_int64
from beginner_tutorials.params import ParamError, read_param
from beginner_tutorials.srv import AddTwoInts, AddTwoIntsResponse

USAGE = "usage: add_two_ints_client.py X Y [--timeout SECONDS]  (X, Y: int64; timeout default ~timeout, 5 s)"


def handle_add_two_ints(req) -> AddTwoIntsResponse:
    total = checked_add(req.a, req.b)
    if total is None:
        rospy.logerr("request refused: %d + %d overflows int64", req.a, req.b)
        raise rospy.ServiceException("%d + %d overflows int64" % (req.a, req.b))
    rospy.loginfo("request: x=%d, y=%d", req.a, req.b)
    rospy.loginfo("sending back response: [%d]", total)
    return AddTwoIntsResponse(total)


def add_two_ints_server() -> None:
    rospy.init_node("add_two_ints_server")
    rospy.Service("add_two_ints", AddTwoInts, handle_add_two_ints)
    rospy.loginfo("Ready to add two ints.")
    rospy.spin()


def _usage_error(problem: str) -> int:
    sys.stderr.write("%s\n%s\n" % (problem, USAGE))
    return 1


def add_two_ints_client(argv: List[str]) -> int:
    """Run the client on argv (remapping arguments already removed); return the exit code."""
    positional, timeout_text = [], None
    args = iter(argv)
    for arg in args:
        if arg == "--timeout":
            timeout_text = next(args, None)
            if timeout_text is None:
                return _usage_error("--timeout needs a number of seconds")
        elif arg.startswith("--timeout="):
            timeout_text = arg[len("--timeout=") :]
        elif arg in ("-h", "--help"):
            return _usage_error("Adds two integers with the add_two_ints service.")
        else:
            positional.append(arg)
    if len(positional) != 2:
        return _usage_error("expected 2 integers, got %d arguments" % len(positional))
    numbers = [parse_int64(text) for text in positional]
    for text, number in zip(positional, numbers):
        if number is None:
            return _usage_error("not an int64 integer: '%s'" % text)

    if not rosgraph.is_master_online():
        sys.stderr.write("no ROS master at %s\n" % rosgraph.get_master_uri())
        return 1
    rospy.init_node("add_two_ints_client", anonymous=True)
    try:
        timeout_s = float(read_param("~timeout", 5.0, (int, float)))
        if timeout_text is not None:
            timeout_s = float(timeout_text)
    except ParamError as error:
        rospy.logfatal(str(error))
        return 1
    except ValueError:
        return _usage_error("--timeout takes seconds, got '%s'" % timeout_text)
    if not 0 < timeout_s <= MAX_TIMEOUT:
        rospy.logfatal("timeout must be in (0, %g] s, got [%g]", MAX_TIMEOUT, timeout_s)
        return 1

    service_name = rospy.resolve_name("add_two_ints")
    try:
        rospy.wait_for_service(service_name, timeout=timeout_s)
    except rospy.ROSException:
        rospy.logerr("service %s did not come up within %g s", service_name, timeout_s)
        return 1
    try:
        response = rospy.ServiceProxy(service_name, AddTwoInts)(*numbers)
    except rospy.ServiceException as error:
        rospy.logerr("Failed to call service %s for %d + %d: %s", service_name, numbers[0], numbers[1], error)
        return 1
    rospy.loginfo("Sum: %d", response.sum)
    return 0
