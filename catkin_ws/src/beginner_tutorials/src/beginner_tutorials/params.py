"""Reading private parameters with the checks roscpp and rospy leave out (twin of params.h)."""
import math
from typing import Any, Tuple, Type, Union

import rospy

_MISSING = object()


class ParamError(Exception):
    """A parameter is missing, of the wrong type or out of range; the message names it and the bad value."""


def read_param(name: str, default: Any = _MISSING, expected: Union[Type, Tuple[Type, ...]] = object) -> Any:
    """Return parameter `name` (default when unset; required when no default is given) checked against `expected`."""
    value = rospy.get_param(name, default)
    if value is _MISSING:
        raise ParamError("Required parameter [%s] is missing" % rospy.resolve_name(name))
    # bool is an int in Python but not in the parameter server's eyes.
    if not isinstance(value, expected) or (isinstance(value, bool) and expected is not bool):
        raise ParamError("Parameter [%s] has the wrong type: [%r]" % (rospy.resolve_name(name), value))
    return value


def read_rate(name: str, default: float) -> float:
    """Return a loop rate in Hz; anything but a finite number > 0 is a ParamError."""
    rate_hz = read_param(name, default, (int, float))
    if not (math.isfinite(rate_hz) and rate_hz > 0):
        raise ParamError("Parameter [%s] must be a rate in Hz > 0, got [%s]" % (rospy.resolve_name(name), rate_hz))
    return float(rate_hz)


def run_node(main_body) -> int:
    """Run a node's body: a ParamError is a fatal start-up error (exit 1), shutdown a normal end."""
    try:
        main_body()
    except ParamError as error:
        rospy.logfatal(str(error))
        return 1
    except rospy.ROSInterruptException:
        pass
    return 0
