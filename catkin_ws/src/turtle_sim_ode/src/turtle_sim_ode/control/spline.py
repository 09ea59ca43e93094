"""joint_trajectory_controller's QuinticSplineSegment: between two states of one joint, a linear, cubic or
quintic polynomial as the states give positions only, velocities too, or accelerations too; outside its time
span a segment holds the end position with zero velocity and acceleration."""
from __future__ import annotations

from dataclasses import dataclass
from typing import List, Optional, Tuple

State = Tuple[float, Optional[float], Optional[float]]  # position, velocity, acceleration (None: not given)


def coefficients(start: State, end: State, duration: float) -> List[float]:
    p0, v0, a0 = start
    p1, v1, a1 = end
    T = duration
    if v0 is None or v1 is None:
        return [p0, 0.0 if T == 0.0 else (p1 - p0) / T, 0.0, 0.0, 0.0, 0.0]
    if T == 0.0:
        return [p0, v0, 0.5 * a0 if (a0 is not None and a1 is not None) else 0.0, 0.0, 0.0, 0.0]
    if a0 is None or a1 is None:
        return [
            p0,
            v0,
            (-3.0 * p0 + 3.0 * p1 - 2.0 * v0 * T - v1 * T) / T**2,
            (2.0 * p0 - 2.0 * p1 + v0 * T + v1 * T) / T**3,
            0.0,
            0.0,
        ]
    T2 = T * T
    return [
        p0,
        v0,
        0.5 * a0,
        (-20.0 * p0 + 20.0 * p1 - 3.0 * a0 * T2 + a1 * T2 - 12.0 * v0 * T - 8.0 * v1 * T) / (2.0 * T**3),
        (30.0 * p0 - 30.0 * p1 + 3.0 * a0 * T2 - 2.0 * a1 * T2 + 16.0 * v0 * T + 14.0 * v1 * T) / (2.0 * T**4),
        (-12.0 * p0 + 12.0 * p1 - a0 * T2 + a1 * T2 - 6.0 * v0 * T - 6.0 * v1 * T) / (2.0 * T**5),
    ]


def evaluate(c: List[float], t: float) -> Tuple[float, float, float]:
    position = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))))
    velocity = c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5])))
    acceleration = 2.0 * c[2] + t * (6.0 * c[3] + t * (12.0 * c[4] + t * 20.0 * c[5]))
    return position, velocity, acceleration


@dataclass
class Segment:
    start_time: float
    end_time: float
    coefs: List[float]

    @classmethod
    def between(cls, start_time: float, start: State, end_time: float, end: State) -> "Segment":
        if end_time < start_time:
            raise ValueError("Quintic spline segment can't be constructed: end_time < start_time.")
        return cls(start_time, end_time, coefficients(start, end, end_time - start_time))

    def sample(self, time: float) -> Tuple[float, float, float]:
        t = time - self.start_time
        if t < 0.0:
            return evaluate(self.coefs, 0.0)[0], 0.0, 0.0
        if t > self.end_time - self.start_time:
            return evaluate(self.coefs, self.end_time - self.start_time)[0], 0.0, 0.0
        return evaluate(self.coefs, t)
