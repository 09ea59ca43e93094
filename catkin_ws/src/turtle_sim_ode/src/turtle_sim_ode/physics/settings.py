"""World-wide solver and contact settings (Gazebo's <physics>), validated, and how they are set on an ODE world."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Tuple

import ode

from turtle_sim_ode.physics import sanity
from turtle_sim_ode.physics.surfaces import SurfaceParams, is_finite
from turtle_sim_ode.physics.trimesh import set_quickstep_w

SOLVERS = ("quick", "world")
# Gravity (m/s² per axis) beyond which resting bodies tunnel through the ground and fall until ODE aborts (1e6 does).
MAX_GRAVITY = 1e3


def configure_world(world: ode.World, params: PhysicsParams) -> None:
    """Gravity and the solver's world-wide settings of ``params`` on an ODE world."""
    world.setGravity(tuple(params.gravity))
    world.setERP(params.erp)
    world.setCFM(params.cfm)
    world.setQuickStepNumIterations(params.solver_iterations)
    world.setContactMaxCorrectingVel(params.contact_max_correcting_vel)
    world.setContactSurfaceLayer(params.contact_surface_layer)
    set_quickstep_w(world, params.sor)


@dataclass
class PhysicsParams:
    """World-wide solver and contact settings."""

    time_step: float = 0.001
    solver: str = "quick"
    solver_iterations: int = 50
    gravity: Tuple[float, float, float] = (0.0, 0.0, -9.81)
    erp: float = 0.2
    cfm: float = 1e-5
    max_contacts: int = 4
    # Caps how fast penetration is pushed out: higher bounces (a 2 m/s impact rebounds
    # at up to this speed), lower lets soft contacts sink under load (force <= cap / cfm).
    contact_max_correcting_vel: float = 0.1
    contact_surface_layer: float = 0.0001
    # The quick step's successive over-relaxation factor (Gazebo's <sor>, ODE's dWorldSetQuickStepW; ODE's own 1.3).
    sor: float = 1.3
    default_surface: SurfaceParams = field(default_factory=SurfaceParams)
    # Gazebo's ground_plane model surface.
    ground_surface: SurfaceParams = field(default_factory=lambda: SurfaceParams(mu=100.0, mu2=50.0))

    def validate(self) -> None:
        """Raise ValueError naming the bad field and its value."""
        if not is_finite(self.time_step) or not 0 < self.time_step <= 0.1:
            raise ValueError(f"time_step must be in (0, 0.1] s, got {self.time_step!r}")
        if self.time_step < sanity.MIN_TIME_STEP:
            raise ValueError(
                f"time_step must be at least {sanity.MIN_TIME_STEP:g} s (shorter steps cannot keep /clock moving at "
                f"any useful rate), got {self.time_step!r}"
            )
        if self.solver not in SOLVERS:
            raise ValueError(f"solver must be one of {SOLVERS}, got {self.solver!r}")
        if (
            not isinstance(self.solver_iterations, int)
            or isinstance(self.solver_iterations, bool)
            or not 1 <= self.solver_iterations <= 1000
        ):
            raise ValueError(f"solver_iterations must be an integer in 1..1000, got {self.solver_iterations!r}")
        if len(self.gravity) != 3 or not all(is_finite(g) and abs(g) <= MAX_GRAVITY for g in self.gravity):
            raise ValueError(f"gravity must be 3 finite numbers within ±{MAX_GRAVITY:g} m/s², got {self.gravity!r}")
        if not is_finite(self.erp) or not 0 <= self.erp <= 1:
            raise ValueError(f"erp must be in [0, 1], got {self.erp!r}")
        if not is_finite(self.cfm) or self.cfm < 0:
            raise ValueError(f"cfm must be finite and >= 0, got {self.cfm!r}")
        if self.cfm > sanity.MAX_CFM:
            raise ValueError(f"cfm must be at most {sanity.MAX_CFM:g}, got {self.cfm!r}")
        if (
            not isinstance(self.max_contacts, int)
            or isinstance(self.max_contacts, bool)
            or not 1 <= self.max_contacts <= 64
        ):
            raise ValueError(f"max_contacts must be an integer in 1..64, got {self.max_contacts!r}")
        for name in ("contact_max_correcting_vel", "contact_surface_layer"):
            value = getattr(self, name)
            if not is_finite(value) or value < 0:
                raise ValueError(f"{name} must be finite and >= 0, got {value!r}")
        if not is_finite(self.sor) or not 0 < self.sor <= 2:
            raise ValueError(f"sor must be in (0, 2], got {self.sor!r}")
        self.default_surface.validate("default_surface")
        self.ground_surface.validate("ground_surface")
