"""Hypothesis settings the workspace's property-based suites share: a bounded number of examples from a fixed seed
in CI (derandomized), and as many as TURTLE_SIM_FUZZ_EXAMPLES asks from the seed TURTLE_SIM_FUZZ_SEED when
scripts/fuzz_sim.sh runs them. Works on Hypothesis 5 (Ubuntu 20.04's)."""
from __future__ import annotations

import os
from typing import Callable

from hypothesis import HealthCheck, seed, settings


def fuzz(default_examples: int) -> Callable:
    """A decorator for a @given test: the settings above and the seed (0 in CI)."""
    chosen_seed = os.environ.get("TURTLE_SIM_FUZZ_SEED")
    configured = settings(
        max_examples=int(os.environ.get("TURTLE_SIM_FUZZ_EXAMPLES", str(default_examples))),
        derandomize=chosen_seed is None,
        deadline=None,
        database=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
    )

    def decorate(test: Callable) -> Callable:
        return configured(seed(int(chosen_seed or 0))(test))

    return decorate
