"""Unit tests of the ROS-free world: kinematics, command timeout, clamping, naming, kill, pen trails."""
from __future__ import annotations

import math
import random

import pytest

from turtlesim.world import (
    COMMAND_TIMEOUT,
    DEFAULT_BACKGROUND,
    DEFAULT_PEN,
    UPDATE_PERIOD,
    WORLD_SIZE,
    World,
    WorldError,
    to_pixels,
    wrap_angle,
)

CENTRE = WORLD_SIZE / 2.0


def world_with_turtle1() -> World:
    world = World()
    world.reset(DEFAULT_BACKGROUND)
    return world


def test_world_is_499_over_45_metres_and_turtle1_starts_in_the_middle():
    assert WORLD_SIZE == pytest.approx(499 / 45)
    turtle = world_with_turtle1().turtles["turtle1"]
    assert (turtle.x, turtle.y, turtle.theta) == (pytest.approx(CENTRE), pytest.approx(CENTRE), 0.0)


def test_one_update_turns_first_then_moves_along_the_new_heading():
    world = world_with_turtle1()
    turtle = world.turtles["turtle1"]
    turtle.command(2.0, 0.5, 1.8, now=0.0)
    world.update(now=0.0)
    theta = 1.8 * UPDATE_PERIOD
    assert turtle.theta == pytest.approx(theta)
    assert turtle.x == pytest.approx(CENTRE + (math.cos(theta) * 2.0 - math.sin(theta) * 0.5) * UPDATE_PERIOD)
    assert turtle.y == pytest.approx(CENTRE + (math.sin(theta) * 2.0 + math.cos(theta) * 0.5) * UPDATE_PERIOD)
    assert turtle.linear_velocity == pytest.approx(math.hypot(2.0, 0.5))


def test_a_second_of_arc_lies_on_the_circle_of_radius_v_over_omega():
    world = world_with_turtle1()
    turtle = world.turtles["turtle1"]
    turtle.command(2.0, 0.0, 1.8, now=0.0)
    radius = 2.0 / 1.8
    for i in range(62):
        world.update(now=i * UPDATE_PERIOD)
        # Centre of the circle: a radius to the left of the start, which faces +x.
        assert math.hypot(turtle.x - CENTRE, turtle.y - (CENTRE + radius)) == pytest.approx(radius, abs=0.02)
    assert turtle.theta == pytest.approx(62 * 1.8 * UPDATE_PERIOD)


def test_a_command_is_obeyed_for_one_second_of_wall_time_then_the_turtle_stands():
    world = world_with_turtle1()
    turtle = world.turtles["turtle1"]
    turtle.command(1.0, 0.0, 0.0, now=10.0)
    world.update(now=10.0 + COMMAND_TIMEOUT - 0.01)
    assert turtle.linear_velocity == 1.0
    world.update(now=10.0 + COMMAND_TIMEOUT + 0.01)
    x = turtle.x
    world.update(now=12.0)
    assert (turtle.linear_velocity, turtle.ang, turtle.x) == (0.0, 0.0, x)


def test_theta_wraps_to_minus_pi_to_pi():
    assert wrap_angle(math.pi) == pytest.approx(-math.pi)
    assert wrap_angle(-math.pi) == pytest.approx(-math.pi)
    assert wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    assert wrap_angle(0.5) == pytest.approx(0.5)


EDGE = 0.01  # m from a wall: one 16 ms update at 2 m/s (0.032 m) crosses it


@pytest.mark.parametrize(
    "start, theta, clamped",
    [
        ((WORLD_SIZE - EDGE, CENTRE), 0.0, (WORLD_SIZE, CENTRE)),  # right wall
        ((EDGE, CENTRE), math.pi, (0.0, CENTRE)),  # left wall
        ((CENTRE, WORLD_SIZE - EDGE), math.pi / 2, (CENTRE, WORLD_SIZE)),  # top wall
        ((CENTRE, EDGE), -math.pi / 2, (CENTRE, 0.0)),  # bottom wall
        ((EDGE, EDGE), -3 * math.pi / 4, (0.0, 0.0)),  # corner
    ],
)
def test_leaving_the_canvas_clamps_and_reports_the_wall(start, theta, clamped):
    world = World()
    world.spawn("t", start[0], start[1], theta)
    turtle = world.turtles["t"]
    turtle.command(2.0, 0.0, 0.0, now=0.0)
    hits = world.update(now=0.0)
    assert [hit.name for hit in hits] == ["t"]
    assert (turtle.x, turtle.y) == (pytest.approx(clamped[0], abs=1e-9), pytest.approx(clamped[1], abs=1e-9))
    # The message gives where the turtle would have been: outside the canvas.
    assert hits[0].message() == "Oh no! I hit the wall! (Clamping from [x=%f, y=%f])" % (hits[0].x, hits[0].y)
    assert not (0.0 <= hits[0].x <= WORLD_SIZE and 0.0 <= hits[0].y <= WORLD_SIZE)


def test_random_drives_stay_on_the_canvas_and_every_clamp_is_reported():
    """Generated inputs beside the hand-picked ones: 200 random commands of random length, seeded."""
    rng = random.Random(17)
    world = world_with_turtle1()
    turtle = world.turtles["turtle1"]
    now = 0.0
    for _ in range(200):
        lin_x, lin_y, ang = rng.uniform(-5, 5), rng.uniform(-2, 2), rng.uniform(-4, 4)
        turtle.command(lin_x, lin_y, ang, now)
        for _ in range(rng.randint(1, 40)):
            x, y, theta = turtle.x, turtle.y, turtle.theta
            hits = world.update(now)
            now += UPDATE_PERIOD
            assert 0.0 <= turtle.x <= WORLD_SIZE and 0.0 <= turtle.y <= WORLD_SIZE
            assert -math.pi <= turtle.theta < math.pi
            expected_theta = wrap_angle(theta + ang * UPDATE_PERIOD)
            free_x = x + (math.cos(expected_theta) * lin_x - math.sin(expected_theta) * lin_y) * UPDATE_PERIOD
            free_y = y + (math.sin(expected_theta) * lin_x + math.cos(expected_theta) * lin_y) * UPDATE_PERIOD
            outside = not (0.0 <= free_x <= WORLD_SIZE and 0.0 <= free_y <= WORLD_SIZE)
            assert bool(hits) == outside
            if not outside:
                assert (turtle.x, turtle.y) == (pytest.approx(free_x), pytest.approx(free_y))


def test_no_wall_report_inside_the_canvas():
    world = world_with_turtle1()
    world.turtles["turtle1"].command(2.0, 0.0, 0.0, now=0.0)
    assert world.update(now=0.0) == []


def test_empty_spawn_names_pick_the_next_free_turtle_n():
    world = world_with_turtle1()
    assert world.spawn("", 2, 2, 0.2) == "turtle2"
    world.spawn("turtle3", 1, 1, 0)
    assert world.spawn("", 3, 3, 0) == "turtle4"
    world.reset(DEFAULT_BACKGROUND)
    assert list(world.turtles) == ["turtle1"]
    assert world.spawn("", 2, 2, 0) == "turtle2"


def test_duplicate_spawn_and_unknown_kill_are_errors():
    world = world_with_turtle1()
    with pytest.raises(WorldError, match=r"A turtle named \[turtle1\] already exists"):
        world.spawn("turtle1", 1, 1, 0)
    with pytest.raises(WorldError, match=r"Tried to kill turtle \[nobody\], which does not exist"):
        world.kill("nobody")
    world.kill("turtle1")
    assert world.turtles == {}


def test_the_pen_draws_the_path_and_the_colour_sensor_sees_it():
    world = world_with_turtle1()
    turtle = world.turtles["turtle1"]
    assert world.colour_under(turtle) == DEFAULT_BACKGROUND
    turtle.command(2.0, 0.0, 0.0, now=0.0)
    for i in range(31):
        world.update(now=i * UPDATE_PERIOD)
    column, row = to_pixels(CENTRE + 0.5, CENTRE)
    assert world.canvas.pixel(int(column), int(row)) == DEFAULT_PEN
    assert world.colour_under(turtle) == DEFAULT_PEN
    # Width 3: one pixel above and below the line are pen, three away is background.
    assert world.canvas.pixel(int(column), int(row) - 1) == DEFAULT_PEN
    assert world.canvas.pixel(int(column), int(row) + 3) == DEFAULT_BACKGROUND
    world.clear((150, 86, 255))
    assert world.colour_under(turtle) == (150, 86, 255)


def test_set_pen_colour_width_and_off():
    world = world_with_turtle1()
    world.set_pen("turtle1", (255, 0, 0), 0, off=False)
    assert world.turtles["turtle1"].pen.width == 3  # width 0 keeps the default
    world.teleport_absolute("turtle1", 1.0, CENTRE, 0.0)
    world.update(now=0.0)
    column, row = to_pixels(3.0, CENTRE)
    assert world.canvas.pixel(int(column), int(row)) == (255, 0, 0)
    world.set_pen("turtle1", (0, 255, 0), 5, off=True)
    world.teleport_absolute("turtle1", 1.0, 2.0, 0.0)
    world.update(now=0.0)
    column, row = to_pixels(1.0, 4.0)
    assert world.canvas.pixel(int(column), int(row)) == DEFAULT_BACKGROUND
    with pytest.raises(WorldError):
        world.set_pen("nobody", (0, 0, 0), 1, off=False)


def test_teleport_relative_turns_then_moves():
    world = world_with_turtle1()
    world.teleport_relative("turtle1", 1.0, math.pi / 2)
    world.update(now=0.0)
    turtle = world.turtles["turtle1"]
    assert (turtle.x, turtle.y, turtle.theta) == (
        pytest.approx(CENTRE),
        pytest.approx(CENTRE + 1.0),
        pytest.approx(math.pi / 2),
    )


# --- issue #26: numbers and names the world cannot use ---------------------------------------------------------------
NON_FINITE = [math.nan, math.inf, -math.inf]


@pytest.mark.parametrize("bad", NON_FINITE)
@pytest.mark.parametrize("field", ["x", "y", "theta"])
def test_non_finite_spawn_and_teleport_values_are_refused_naming_them(bad, field):
    world = world_with_turtle1()
    values = {"x": 1.0, "y": 1.0, "theta": 0.0}
    values[field] = bad
    with pytest.raises(WorldError, match="%s \\[%r\\] is not a finite number" % (field, bad)):
        world.spawn("t2", **values)
    assert "t2" not in world.turtles
    with pytest.raises(WorldError, match="not a finite number"):
        world.teleport_absolute("turtle1", **values)
    with pytest.raises(WorldError, match="not a finite number"):
        world.teleport_relative("turtle1", bad if field == "x" else 1.0, bad if field != "x" else 0.0)
    world.update(0.0)
    turtle = world.turtles["turtle1"]
    assert (turtle.x, turtle.y, turtle.theta) == (CENTRE, CENTRE, 0.0)


@pytest.mark.parametrize("component", range(3))
def test_a_non_finite_command_is_refused_and_the_last_one_kept(component):
    world = world_with_turtle1()
    turtle = world.turtles["turtle1"]
    turtle.command(1.0, 0.0, 0.5, 0.0)
    command = [1.0, 0.0, 0.5]
    command[component] = math.nan
    with pytest.raises(WorldError, match="cmd_vel of turtle \\[turtle1\\]"):
        turtle.command(*command, now=0.1)
    assert (turtle.lin_x, turtle.lin_y, turtle.ang, turtle.last_command) == (1.0, 0.0, 0.5, 0.0)


@pytest.mark.parametrize("name", ["a b", "1abc", "a-b", "a//b", "a/", "é", "a\nb", "/", "~", "_a"])
def test_names_that_are_not_legal_ros_graph_names_are_refused(name):
    """As ros_tutorials' turtlesim, whose spawn fails where ros::NodeHandle(name) throws an InvalidNameException."""
    world = world_with_turtle1()
    with pytest.raises(WorldError, match="not a legal ROS graph name"):
        world.spawn(name, 1.0, 1.0, 0.0)
    assert list(world.turtles) == ["turtle1"]


@pytest.mark.parametrize("name", ["a", "turtle2", "a/b", "/global", "~private", "A_1/b2"])
def test_legal_ros_graph_names_are_spawned(name):
    world = world_with_turtle1()
    assert world.spawn(name, 1.0, 1.0, 0.0) == name


def test_the_update_survives_an_exception_in_one_turtle(monkeypatch):
    world = world_with_turtle1()
    world.spawn("broken", 2.0, 2.0, 0.0)
    world.turtles["turtle1"].command(1.0, 0.0, 0.0, 0.0)
    original = World._update_turtle

    def failing(self, turtle, now, dt):
        if turtle.name == "broken":
            raise OverflowError("cannot convert float infinity to integer")
        return original(self, turtle, now, dt)

    monkeypatch.setattr(World, "_update_turtle", failing)
    world.update(0.0)
    world.update(0.016)
    assert world.turtles["turtle1"].x == pytest.approx(CENTRE + 2 * UPDATE_PERIOD)
    assert (world.turtles["broken"].x, world.turtles["broken"].y) == (2.0, 2.0)
    faults = world.take_faults()
    assert len(faults) == 2 and "turtle [broken]" in faults[0] and "OverflowError" in faults[0]
    assert world.take_faults() == []


@pytest.mark.parametrize("far", [1e300, 1.7e308, -1.7e308])
def test_teleports_to_absurd_but_finite_places_end_on_the_wall(far):
    world = world_with_turtle1()
    world.teleport_absolute("turtle1", far, far, 0.0)
    world.teleport_relative("turtle1", far, 0.0)
    world.teleport_relative("turtle1", far, 0.0)
    world.update(0.0)
    turtle = world.turtles["turtle1"]
    assert 0.0 <= turtle.x <= WORLD_SIZE and 0.0 <= turtle.y <= WORLD_SIZE and math.isfinite(turtle.theta)
    assert world.take_faults() == []
