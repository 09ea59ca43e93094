"""rqt_plot's command line, without ROS: which fields to plot and how to start."""
from __future__ import annotations

import argparse
from typing import Callable, List, Optional, Sequence

import rosgraph.names


def resolve_for_rqt_plot(name: str) -> str:
    """A relative name on the command line is resolved in the tool's namespace, as rosgraph resolves a script's."""
    return rosgraph.names.script_resolve_name("rqt_plot", name)


def expand_field_argument(argument: str) -> List[str]:
    """'/a/b,/c/d' -> ['/a/b', '/c/d']; '/turtle1/pose/x:y:theta' -> the three fields of /turtle1/pose.

    Raises ValueError for a ':' list whose first item names no topic ('x:y').
    """
    fields = []
    for item in (part for part in argument.split(",") if part):
        if ":" not in item:
            fields.append(item)
            continue
        first, *others = item.split(":")
        if "/" not in first:
            raise ValueError("%s must contain a topic and field name" % item)
        fields.append(first)
        base = first[: first.rfind("/")]
        fields.extend("%s/%s" % (base, other) for other in others if other)
    return fields


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="rqt_plot", description="Plot numeric fields of ROS topics over time.")
    parser.add_argument("-P", "--pause", action="store_true", dest="start_paused", help="start in paused state")
    parser.add_argument(
        "-e", "--empty", action="store_true", dest="start_empty", help="start without restoring previous topics"
    )
    parser.add_argument(
        "--buffer-size",
        type=int,
        default=20000,
        help="points kept per curve, the oldest dropped first (default 20000: 5 min 20 s at 62.5 Hz)",
    )
    parser.add_argument(
        "topics", nargs="*", default=[], help="fields to plot: /topic/field, /topic/f1:f2:f3, /a/b,/c/d"
    )
    return parser


def parse_arguments(
    argv: Sequence[str], resolve: Optional[Callable[[str], str]] = resolve_for_rqt_plot
) -> argparse.Namespace:
    """The parsed command line; .topics holds resolved field names. Exits with a usage message on bad input."""
    parser = build_parser()
    args = parser.parse_args(list(argv))
    if args.buffer_size < 2:
        parser.error("--buffer-size must be at least 2, got %d" % args.buffer_size)
    fields = []
    for argument in args.topics:
        try:
            fields.extend(expand_field_argument(argument))
        except ValueError as error:
            parser.error(str(error))
    args.topics = [resolve(field) for field in fields] if resolve else fields
    return args
