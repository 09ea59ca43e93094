"""Which fields of a message can be plotted, and reading one from a message. No master: the published topics and
their types are given, and message classes come from a loader (roslib.message.get_message_class in the tool)."""
from __future__ import annotations

import re
from typing import Any, Callable, Dict, List, Optional, Tuple

NUMERIC_TYPES = frozenset(
    ("bool", "byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64")
    + ("float32", "float64")
)
# time and duration are plotted through their two integer parts, as the message classes hold them
TIME_FIELDS = (("secs", "int32"), ("nsecs", "int32"))
SLOT_TYPE = re.compile(r"^([^\[\]]+)(\[(\d*)\])?$")
FIELD_STEP = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(\[(\d+)\])?$")

ClassLoader = Callable[[str], Any]


def parse_slot_type(slot_type: str) -> Tuple[str, bool, Optional[int]]:
    """'float64[9]' -> ('float64', True, 9); 'uint8[]' -> ('uint8', True, None); 'int32' -> ('int32', False, None)."""
    match = SLOT_TYPE.match(slot_type)
    if not match:
        raise ValueError("not a message field type: %s" % slot_type)
    size = match.group(3)
    return match.group(1), match.group(2) is not None, int(size) if size else None


def sub_fields(type_name: str, load_class: ClassLoader) -> List[Tuple[str, str]]:
    """[(field name, slot type)] of a compound type; [] for a primitive or unknown one."""
    if type_name in ("time", "duration"):
        return list(TIME_FIELDS)
    if type_name in NUMERIC_TYPES or type_name == "string":
        return []
    message_class = load_class(type_name)
    if message_class is None:
        return []
    return list(zip(message_class.__slots__, message_class._slot_types))


def completions(topic: str, type_name: str, load_class: ClassLoader, max_array: int = 64) -> List[str]:
    """Every name under a topic the Topic box offers: the topic, its sub-messages and numeric fields, the elements
    of fixed-size arrays by index (up to max_array of them). Variable-size arrays have no known length: an index
    typed by hand is taken (plot_fields)."""
    names = [topic]

    def walk(prefix: str, slot_type: str) -> None:
        base, is_array, size = parse_slot_type(slot_type)
        if is_array:
            if size is None or size > max_array:
                return
            for index in range(size):
                element = "%s[%d]" % (prefix, index)
                names.append(element)
                walk_compound(element, base)
            return
        if base in NUMERIC_TYPES:
            names.append(prefix)
            return
        walk_compound(prefix, base)

    def walk_compound(prefix: str, base: str) -> None:
        fields = sub_fields(base, load_class)
        if fields and prefix != topic:
            names.append(prefix)
        for name, field_type in fields:
            walk("%s/%s" % (prefix, name), field_type)

    walk_compound(topic, type_name)
    return list(dict.fromkeys(names))


def split_topic(path: str, topic_types: Dict[str, str]) -> Optional[Tuple[str, str, str]]:
    """(topic, its type, field path inside the message) of a published topic that path names or goes into."""
    for topic in sorted(topic_types, key=len, reverse=True):
        if path == topic or path.startswith(topic + "/"):
            return topic, topic_types[topic], path[len(topic) :].strip("/")
    return None


def field_type(type_name: str, field: str, load_class: ClassLoader) -> Tuple[str, bool, Optional[int]]:
    """The parsed slot type that field (a/b[2]/c) of a message of type_name has. Raises ValueError if none."""
    current: Tuple[str, bool, Optional[int]] = (type_name, False, None)
    for step in (part for part in field.split("/") if part):
        match = FIELD_STEP.match(step)
        if not match:
            raise ValueError("invalid field %s" % step)
        known = dict(sub_fields(current[0], load_class))
        if current[1] or match.group(1) not in known:
            raise ValueError("no field %s in %s" % (step, current[0]))
        current = parse_slot_type(known[match.group(1)])
        if match.group(3) is not None:
            if not current[1]:
                raise ValueError("%s is not an array" % match.group(1))
            if current[2] is not None and int(match.group(3)) >= current[2]:
                raise ValueError("index %s out of %s[%d]" % (match.group(3), match.group(1), current[2]))
            current = (current[0], False, None)
    return current


def plot_fields(path: str, topic_types: Dict[str, str], load_class: ClassLoader) -> Tuple[List[str], str]:
    """The curves that adding path gives, and a message saying why (as rqt_plot's get_plot_fields): a numeric
    field itself; each element of a fixed-size numeric array; each numeric, non-array field of a message."""
    found = split_topic(path, topic_types)
    if found is None:
        return [], "topic %s does not exist" % path
    topic, type_name, field = found
    try:
        base, is_array, size = field_type(type_name, field, load_class)
    except ValueError as error:
        return [], "%s (topic %s)" % (error, topic)
    path = path.rstrip("/")
    if base in NUMERIC_TYPES:
        if not is_array:
            return [path], "%s is numeric" % path
        if size is None:
            return [], "%s is a variable-size array: give an index, %s[0]" % (path, path)
        return ["%s[%d]" % (path, index) for index in range(size)], "%s is a fixed-size numeric array" % path
    if is_array:
        return [], "%s is an array of %s: give an index" % (path, base)
    numeric = [name for name, slot in sub_fields(base, load_class) if slot in NUMERIC_TYPES]
    if not numeric:
        return [], "no plottable fields in %s" % path
    return ["%s/%s" % (path, name) for name in numeric], "%d plottable fields in %s" % (len(numeric), path)


class FieldReader:
    """Reads one field path (pose/position/x, data[3]) out of a message as a float."""

    def __init__(self, field: str) -> None:
        self._steps = []
        for step in (part for part in field.split("/") if part):
            match = FIELD_STEP.match(step)
            if not match:
                raise ValueError("invalid field %s" % step)
            self._steps.append((match.group(1), None if match.group(3) is None else int(match.group(3))))

    def __call__(self, message: Any) -> float:
        """Raises LookupError (a missing element of a variable array) or TypeError/ValueError (not numeric)."""
        value = message
        for name, index in self._steps:
            value = getattr(value, name)
            if index is not None:
                value = value[index]
        if isinstance(value, bytes):  # uint8[N] arrays come as bytes: an index gives an int, a whole one does not
            raise TypeError("bytes are not a number")
        return float(value)
