"""Guard against per-step cost regressions (one TurtleBot, diff drive, 1 ms, quick 50): a step of the world (collision
in the contact kernel, the drive, the hooks, ODE's quickStep) against ODE's quickStep alone on the same world, both
timed in this run. Typical on the 2-core dev machine: 42 us against 30 us (1.4 x). The bound is loose so that a busy
machine does not fail it; a per-step allocation spree or an accidental O(n^2) collision pass would.
"""
from conftest import TurtleSim
from workspace_testing.timing import assert_within, best_seconds

STEPS = 1000
BOUND_RATIO = 4.0


def test_step_cost_stays_low():
    sim = TurtleSim("quick")
    sim.drive.params.cmd_timeout = 0.0
    sim.drive.set_command(0.3, 0.3, 0.0)
    dt = sim.physics.time_step

    def steps() -> None:
        for _ in range(STEPS):
            sim.drive.update(sim.physics.sim_time, dt)
            sim.physics.step()

    full = best_seconds(steps, 5)
    assert sim.physics.contact_count == 4  # 2 wheels (line contacts merged) + 2 casters
    quick_steps_alone = best_seconds(lambda: [sim.physics.world.quickStep(dt) for _ in range(STEPS)], 5)
    assert_within(full, quick_steps_alone, BOUND_RATIO, "%d steps" % STEPS)
