"""Property-based tests of turtlesim's world (issue #26): generated sequences of what its services and topics hand it
(spawn, kill, teleport_absolute, teleport_relative, set_pen, cmd_vel), with NaN, infinities, huge and tiny numbers,
and careless or hostile names. After each request and each update, whatever came: a bad value is a WorldError
(what the node turns into a failed call or a throttled warning) and changes nothing; every turtle's state is finite
and on the canvas; no turtle's update failed; no update took more than 50 times the time of 1000 updates of a world
with one turtle (measured in the same run).

CI runs a bounded number of examples with a fixed seed (derandomize); scripts/fuzz_sim.sh runs many more
(TURTLE_SIM_FUZZ_EXAMPLES, TURTLE_SIM_FUZZ_SEED)."""
from __future__ import annotations

import math
import sys
from typing import List, Tuple

from hypothesis import event, given
from hypothesis import strategies as st
from workspace_testing.fuzz import fuzz
from workspace_testing.timing import assert_within, best_seconds, timed

from turtlesim.world import DEFAULT_BACKGROUND, UPDATE_PERIOD, WORLD_SIZE, World, WorldError

ANSWER_WITHIN_REFERENCES = 50  # an update may take this many times the reference below, timed in the same run


def thousand_updates_of_one_turtle() -> None:
    world = World()
    world.turtle(world.reset(DEFAULT_BACKGROUND)).command(2.0, 0.0, 1.0, 0.0)  # drawing as it turns
    for step in range(1000):
        world.update(step * UPDATE_PERIOD)


REFERENCE_SECONDS = best_seconds(thousand_updates_of_one_turtle)

hostile = st.sampled_from([math.nan, math.inf, -math.inf, 1e308, -1e308, 1.7e308, 5e-324, -0.0, 1e150, 2**53])
values = st.one_of(
    st.floats(min_value=-20.0, max_value=20.0).map(lambda v: 0.0 if abs(v) < sys.float_info.min else v),
    hostile,
    st.floats(allow_nan=True, allow_infinity=True),
)
names = st.one_of(
    st.sampled_from(["", "turtle1", "turtle2", "t", "a b", "/g", "~p", "a/b", "a//b", "1x", "x-y", "é", "a/"]),
    st.text(max_size=8),
)
bytes_ = st.integers(min_value=0, max_value=255)
requests = st.one_of(
    st.tuples(st.just("spawn"), names, values, values, values),
    st.tuples(st.just("kill"), names),
    st.tuples(st.just("teleport_absolute"), names, values, values, values),
    st.tuples(st.just("teleport_relative"), names, values, values),
    st.tuples(st.just("set_pen"), names, bytes_, bytes_, bytes_, bytes_, st.booleans()),
    st.tuples(st.just("cmd_vel"), names, values, values, values),
    st.tuples(st.just("update"), st.integers(min_value=1, max_value=80)),
)


def apply(world: World, request: Tuple, now: float) -> None:
    kind, args = request[0], request[1:]
    if kind == "spawn":
        world.spawn(*args)
    elif kind == "kill":
        world.kill(*args)
    elif kind == "teleport_absolute":
        world.teleport_absolute(*args)
    elif kind == "teleport_relative":
        world.teleport_relative(*args)
    elif kind == "set_pen":
        name, r, g, b, width, off = args
        world.set_pen(name, (r, g, b), width, off)
    elif kind == "cmd_vel":
        name, lin_x, lin_y, ang = args
        world.turtle(name).command(lin_x, lin_y, ang, now)


def assert_sane(world: World) -> None:
    for turtle in world.turtles.values():
        state = (turtle.x, turtle.y, turtle.theta, turtle.lin_x, turtle.lin_y, turtle.ang)
        assert all(math.isfinite(v) for v in state), (turtle.name, state)
        assert 0.0 <= turtle.x <= WORLD_SIZE and 0.0 <= turtle.y <= WORLD_SIZE, (turtle.name, state)
        assert -math.pi <= turtle.theta <= math.pi, (turtle.name, state)


@fuzz(60)
@given(sequence=st.lists(requests, min_size=1, max_size=25))
def test_generated_requests_are_refused_cleanly_or_obeyed_and_every_turtle_stays_finite(sequence: List[Tuple]) -> None:
    world = World()
    world.reset(DEFAULT_BACKGROUND)
    now = 0.0
    for request in sequence:
        if request[0] == "update":
            for _ in range(request[1]):
                _, seconds = timed(lambda: world.update(now))
                assert_within(seconds, REFERENCE_SECONDS, ANSWER_WITHIN_REFERENCES, "an update")
                now += UPDATE_PERIOD
                assert world.take_faults() == []
                assert_sane(world)
            continue
        before = {name: (t.x, t.y, t.theta, len(t.teleports)) for name, t in world.turtles.items()}
        try:
            apply(world, request, now)
            event("%s accepted" % request[0])
        except WorldError as error:
            event("%s refused" % request[0])
            assert str(error)
            after = {name: (t.x, t.y, t.theta, len(t.teleports)) for name, t in world.turtles.items()}
            assert after == before  # a refusal changes nothing
    world.update(now)
    assert world.take_faults() == []
    assert_sane(world)
