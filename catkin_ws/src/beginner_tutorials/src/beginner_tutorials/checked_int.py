"""ROS-free integer helpers shared by the add_two_ints server and client (twin of checked_int.h)."""
import re
from typing import Optional

INT64_MIN = -(2**63)
INT64_MAX = 2**63 - 1
MAX_TIMEOUT = 86400.0  # the longest wait for a service that the clients accept, in seconds (one day)
_INTEGER = re.compile(r"[+-]?[0-9]+\Z")


def parse_int64(text: str) -> Optional[int]:
    """Return the whole decimal integer in text ("42", "-7", "+3"), or None if it is not one or not an int64."""
    if not _INTEGER.match(text):
        return None
    value = int(text)
    return value if INT64_MIN <= value <= INT64_MAX else None


def checked_add(a: int, b: int) -> Optional[int]:
    """Return a + b, or None when the sum does not fit in int64."""
    total = a + b
    return total if INT64_MIN <= total <= INT64_MAX else None
