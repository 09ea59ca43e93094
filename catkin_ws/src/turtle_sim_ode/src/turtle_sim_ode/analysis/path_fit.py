"""ROS-free fits to recorded planar paths (the circle a drive traces), for tests and the benchmark."""
from __future__ import annotations

import math
from typing import Sequence, Tuple


def fit_circle(points: Sequence[Sequence[float]]) -> Tuple[Tuple[float, float], float]:
    """Least-squares (Kasa) circle through (x, y) points: centre and radius."""
    n = len(points)
    mean_x = sum(p[0] for p in points) / n
    mean_y = sum(p[1] for p in points) / n
    u = [(p[0] - mean_x, p[1] - mean_y) for p in points]
    suu = sum(a * a for a, _ in u)
    svv = sum(b * b for _, b in u)
    suv = sum(a * b for a, b in u)
    r1 = sum(a * (a * a + b * b) for a, b in u) / 2
    r2 = sum(b * (a * a + b * b) for a, b in u) / 2
    det = suu * svv - suv * suv
    centre_u, centre_v = (r1 * svv - r2 * suv) / det, (r2 * suu - r1 * suv) / det
    return (mean_x + centre_u, mean_y + centre_v), math.sqrt(
        centre_u * centre_u + centre_v * centre_v + (suu + svv) / n
    )
