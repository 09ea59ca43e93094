"""Guard against per-step cost regressions (one TurtleBot, diff drive, 1 ms, quick 50).

Typical on the 2-core dev machine: ~50 us/step, ~31 us of it inside ODE's quickStep.
The bound is loose so that a busy CI machine does not fail it; a per-step allocation
spree or an accidental O(n^2) collision pass would.
"""
import time

from conftest import TurtleSim

STEPS = 1000
BOUND_US = 250.0


def test_step_cost_stays_low():
    sim = TurtleSim("quick")
    sim.drive.params.cmd_timeout = 0.0
    sim.drive.set_command(0.3, 0.3, 0.0)
    dt = sim.physics.time_step
    best = float("inf")
    for _ in range(5):
        start = time.perf_counter()
        for _ in range(STEPS):
            sim.drive.update(sim.physics.sim_time, dt)
            sim.physics.step()
        best = min(best, (time.perf_counter() - start) / STEPS * 1e6)
    assert sim.physics.contact_count == 4  # 2 wheels (line contacts merged) + 2 casters
    assert best < BOUND_US, f"{best:.1f} us per step"
