"""The turtles' world without ROS: kinematics, the 1 s command timeout, wall clamping, spawn/kill naming and the
pen trails on a pixel canvas. The ROS interface (ros_node.py) feeds it commands and wall-clock times and publishes
what it reports.

Coordinates: metres, x to the right and y up, origin at the canvas' bottom-left corner, theta in [-pi, pi).
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

from turtlesim.canvas import Canvas, Rgb

CANVAS_PIXELS = 500  # the canvas is square
PIXELS_PER_METRE = 45.0
WORLD_SIZE = (CANVAS_PIXELS - 1) / PIXELS_PER_METRE  # metres, about 11.09
UPDATE_PERIOD = 0.016  # s per update
COMMAND_TIMEOUT = 1.0  # s of wall time a cmd_vel is obeyed for
DEFAULT_BACKGROUND: Rgb = (69, 86, 255)
DEFAULT_PEN: Rgb = (179, 184, 255)
DEFAULT_PEN_WIDTH = 3


# A legal ROS graph name (ros::names::validate, rosgraph.names.is_legal_name): a letter (after an optional '/' or
# '~'), then letters, digits, '_' and single '/'s, not ending in '/'. Turtle names prefix topic and service names.
LEGAL_NAME = re.compile(r"[~/]?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z0-9_]+)*")


class WorldError(Exception):
    """A request the world refuses (duplicate or unknown turtle name, a bad name or number); the message says why."""


def finite(what: str, **values: float) -> None:
    """WorldError naming the first value that is not a finite number."""
    for name, value in values.items():
        if not math.isfinite(value):
            raise WorldError("%s: %s [%r] is not a finite number" % (what, name, value))


def wrap_angle(theta: float) -> float:
    """theta wrapped to [-pi, pi), as the original wraps it (theta - 2 pi floor((theta + pi) / 2 pi)); for angles so
    large that this loses every digit (1e300 rad), with the exact remainder instead."""
    wrapped = theta - 2.0 * math.pi * math.floor((theta + math.pi) / (2.0 * math.pi))
    if -math.pi <= wrapped < math.pi:
        return wrapped
    remainder = math.fmod(theta + math.pi, 2.0 * math.pi)
    return (remainder + 2.0 * math.pi if remainder < 0.0 else remainder) - math.pi


@dataclass
class Pen:
    colour: Rgb = DEFAULT_PEN
    width: int = DEFAULT_PEN_WIDTH
    on: bool = True


@dataclass
class WallHit:
    """A turtle left the canvas and was put back on its edge; x, y is where it would have been."""

    name: str
    x: float
    y: float

    def message(self) -> str:
        return "Oh no! I hit the wall! (Clamping from [x=%f, y=%f])" % (self.x, self.y)


@dataclass
class Turtle:
    name: str
    x: float
    y: float
    theta: float
    lin_x: float = 0.0
    lin_y: float = 0.0
    ang: float = 0.0
    last_command: Optional[float] = None  # wall time of the last cmd_vel
    pen: Pen = field(default_factory=Pen)
    # Teleports wait for the next update, in order: ("absolute", x, y, theta) or ("relative", linear, angular).
    teleports: List[Tuple[str, float, float, float]] = field(default_factory=list)

    @property
    def linear_velocity(self) -> float:
        return math.hypot(self.lin_x, self.lin_y)

    def command(self, lin_x: float, lin_y: float, ang: float, now: float) -> None:
        """A cmd_vel received at wall time `now`: obeyed until COMMAND_TIMEOUT has passed; WorldError (and no
        change) if a component is not finite."""
        finite("cmd_vel of turtle [%s]" % self.name, linear_x=lin_x, linear_y=lin_y, angular_z=ang)
        self.lin_x, self.lin_y, self.ang = lin_x, lin_y, ang
        self.last_command = now


def to_pixels(x: float, y: float) -> Tuple[float, float]:
    """World metres -> canvas pixel coordinates (column, row), row 0 at the top."""
    return x * PIXELS_PER_METRE, (WORLD_SIZE - y) * PIXELS_PER_METRE


class World:
    """Every turtle and the canvas under them. Not thread-safe: the caller holds a lock."""

    def __init__(self, background: Rgb = DEFAULT_BACKGROUND):
        self.canvas = Canvas(CANVAS_PIXELS, CANVAS_PIXELS, background)
        self.turtles: Dict[str, Turtle] = {}
        self._id_counter = 0
        self.faults: List[str] = []  # turtles whose update failed, since take_faults

    # --- turtles -------------------------------------------------------------------------------------------------
    def spawn(self, name: str, x: float, y: float, theta: float) -> str:
        """Add a turtle and return its name; an empty name picks the next free `turtleN`."""
        if not name:
            while True:
                self._id_counter += 1
                name = "turtle%d" % self._id_counter
                if name not in self.turtles:
                    break
        elif name in self.turtles:
            raise WorldError("A turtle named [%s] already exists" % name)
        elif not LEGAL_NAME.fullmatch(name):
            raise WorldError("Cannot spawn turtle [%s]: not a legal ROS graph name" % name)
        finite("Cannot spawn turtle [%s]" % name, x=x, y=y, theta=theta)
        self.turtles[name] = Turtle(name, float(x), float(y), float(theta))
        return name

    def kill(self, name: str) -> None:
        if name not in self.turtles:
            raise WorldError("Tried to kill turtle [%s], which does not exist" % name)
        del self.turtles[name]

    def turtle(self, name: str) -> Turtle:
        try:
            return self.turtles[name]
        except KeyError:
            raise WorldError("No turtle named [%s]" % name) from None

    def clear(self, background: Rgb) -> None:
        """Wipe every pen trail: the canvas becomes `background`."""
        self.canvas.fill(background)

    def reset(self, background: Rgb) -> str:
        """Remove every turtle, restart the naming, spawn turtle1 in the middle and clear the canvas."""
        self.turtles.clear()
        self._id_counter = 0
        name = self.spawn("", WORLD_SIZE / 2.0, WORLD_SIZE / 2.0, 0.0)
        self.clear(background)
        return name

    def set_pen(self, name: str, colour: Rgb, width: int, off: bool) -> None:
        """As turtlesim's set_pen: `off` lifts the pen (keeping its colour); width 0 keeps the default width."""
        turtle = self.turtle(name)
        if off:
            turtle.pen.on = False
            return
        turtle.pen = Pen(tuple(colour), width if width != 0 else DEFAULT_PEN_WIDTH, True)

    def teleport_absolute(self, name: str, x: float, y: float, theta: float) -> None:
        turtle = self.turtle(name)
        finite("teleport_absolute of turtle [%s]" % name, x=x, y=y, theta=theta)
        turtle.teleports.append(("absolute", x, y, theta))

    def teleport_relative(self, name: str, linear: float, angular: float) -> None:
        turtle = self.turtle(name)
        finite("teleport_relative of turtle [%s]" % name, linear=linear, angular=angular)
        turtle.teleports.append(("relative", linear, angular, 0.0))

    # --- time ----------------------------------------------------------------------------------------------------
    def update(self, now: float, dt: float = UPDATE_PERIOD) -> List[WallHit]:
        """Move every turtle by one update of `dt` seconds at wall time `now`; return the wall hits. A turtle whose
        update fails (nothing known does) is stopped where it stood and named in ``faults``; the others move on."""
        hits = []
        for turtle in self.turtles.values():
            before = (turtle.x, turtle.y, turtle.theta)
            try:
                hit = self._update_turtle(turtle, now, dt)
            except Exception as error:
                turtle.x, turtle.y, turtle.theta = before
                turtle.lin_x = turtle.lin_y = turtle.ang = 0.0
                turtle.teleports.clear()
                self.faults.append("turtle [%s] not moved: %s: %s" % (turtle.name, type(error).__name__, error))
                continue
            if hit is not None:
                hits.append(hit)
        return hits

    def take_faults(self) -> List[str]:
        found, self.faults = self.faults, []
        return found

    def _update_turtle(self, turtle: Turtle, now: float, dt: float) -> Optional[WallHit]:
        for kind, a, b, c in turtle.teleports:
            old = (turtle.x, turtle.y)
            if kind == "relative":
                turtle.theta += b
                turtle.x += math.cos(turtle.theta) * a
                turtle.y += math.sin(turtle.theta) * a
            else:
                turtle.x, turtle.y, turtle.theta = a, b, c
            if not (math.isfinite(turtle.x) and math.isfinite(turtle.y)):  # relative jumps summed past 1e308 m
                turtle.x = min(max(turtle.x, 0.0), WORLD_SIZE) if not math.isnan(turtle.x) else old[0]
                turtle.y = min(max(turtle.y, 0.0), WORLD_SIZE) if not math.isnan(turtle.y) else old[1]
            self._draw(turtle, old)
        turtle.teleports.clear()

        if turtle.last_command is None or now - turtle.last_command > COMMAND_TIMEOUT:
            turtle.lin_x = turtle.lin_y = turtle.ang = 0.0

        old = (turtle.x, turtle.y)
        # Turn first, then move along the new heading (as ros_tutorials' turtlesim does).
        turtle.theta = wrap_angle(turtle.theta + turtle.ang * dt)
        cos_t, sin_t = math.cos(turtle.theta), math.sin(turtle.theta)
        turtle.x += (cos_t * turtle.lin_x - sin_t * turtle.lin_y) * dt
        turtle.y += (sin_t * turtle.lin_x + cos_t * turtle.lin_y) * dt

        hit = None
        if not (0.0 <= turtle.x <= WORLD_SIZE and 0.0 <= turtle.y <= WORLD_SIZE):
            hit = WallHit(turtle.name, turtle.x, turtle.y)
            turtle.x = min(max(turtle.x, 0.0), WORLD_SIZE)
            turtle.y = min(max(turtle.y, 0.0), WORLD_SIZE)
        if (turtle.x, turtle.y) != old:
            self._draw(turtle, old)
        return hit

    def _draw(self, turtle: Turtle, old: Tuple[float, float]) -> None:
        if turtle.pen.on:
            self.canvas.draw_line(to_pixels(*old), to_pixels(turtle.x, turtle.y), turtle.pen.colour, turtle.pen.width)

    def colour_under(self, turtle: Turtle) -> Rgb:
        """The canvas colour (background or pen trail) under the turtle's centre."""
        column, row = to_pixels(turtle.x, turtle.y)
        return self.canvas.pixel(int(round(column)), int(round(row)))
