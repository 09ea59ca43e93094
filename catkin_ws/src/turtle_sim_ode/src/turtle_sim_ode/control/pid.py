"""control_toolbox's Pid (noetic): gains p, i, d, i_clamp (i_clamp_min/max), antiwindup, as Pid::init reads
them, and Pid::computeCommand's arithmetic."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

from turtle_sim_ode.control.params import ControllerError, Params


@dataclass
class PidGains:
    p: float = 0.0
    i: float = 0.0
    d: float = 0.0
    i_max: float = 0.0
    i_min: float = 0.0
    antiwindup: bool = False


def read_gains(params: Params) -> PidGains:
    """Pid::init: p is required; i, d and i_clamp default to 0; i_clamp_min/max override each side."""
    if not params.has("p"):
        raise ControllerError(f"No p gain specified for pid.  Namespace: {params.namespace}")
    i_clamp = abs(params.number("i_clamp", 0.0))
    return PidGains(
        p=params.number("p"),
        i=params.number("i", 0.0),
        d=params.number("d", 0.0),
        i_max=abs(params.number("i_clamp_max", i_clamp)),
        i_min=-abs(params.number("i_clamp_min", -i_clamp)),
        antiwindup=params.flag("antiwindup", False),
    )


class Pid:
    def __init__(self, gains: Optional[PidGains] = None) -> None:
        self.gains = gains or PidGains()
        self.reset()

    def reset(self) -> None:
        self.p_error_last = 0.0
        self.valid_p_error_last = False
        self.p_error = 0.0
        self.i_error = 0.0
        self.d_error = 0.0
        self.command = 0.0

    def compute(self, error: float, dt: float, error_dot: Optional[float] = None) -> float:
        """The command for this error; without error_dot, the derivative is the error's finite difference."""
        if error_dot is None:
            if dt == 0.0 or not math.isfinite(error):
                return 0.0
            error_dot = self.d_error
            if dt > 0.0:
                if self.valid_p_error_last:
                    error_dot = (error - self.p_error_last) / dt
                self.p_error_last = error
                self.valid_p_error_last = True
        gains = self.gains
        self.p_error = error
        self.d_error = error_dot
        if dt == 0.0 or not math.isfinite(error) or not math.isfinite(error_dot):
            return 0.0
        p_term = gains.p * error
        self.i_error += dt * error
        if gains.antiwindup and gains.i != 0.0:
            low, high = sorted((gains.i_min / gains.i, gains.i_max / gains.i))
            self.i_error = min(max(self.i_error, low), high)
        i_term = gains.i * self.i_error
        if not gains.antiwindup:
            i_term = min(max(i_term, gains.i_min), gains.i_max)
        self.command = p_term + i_term + gains.d * error_dot
        return self.command
