"""Mass properties of bodies made of several links: the inertia of parts about their common centre of mass, an
inertia turned into another frame."""
from __future__ import annotations

from typing import Sequence, Tuple

from turtle_sim_ode.models.transforms import Matrix3, Quat, Vec3, quat_matrix


def inertia_about_com(parts: Sequence[Tuple[float, Vec3, Matrix3]]) -> Tuple[float, Vec3, Matrix3]:
    """Total mass, COM and inertia about the COM of point-mass-plus-inertia parts."""
    mass = sum(m for m, _, _ in parts)
    com = tuple(sum(m * c[i] for m, c, _ in parts) / mass for i in range(3))
    inertia = [[0.0] * 3 for _ in range(3)]
    for m, c, local in parts:
        d = [c[i] - com[i] for i in range(3)]
        d2 = d[0] ** 2 + d[1] ** 2 + d[2] ** 2
        for r in range(3):
            for k in range(3):
                # Parallel-axis theorem: I + m(|d|^2 E - d d^T).
                inertia[r][k] += local[r][k] + m * ((d2 if r == k else 0.0) - d[r] * d[k])
    return mass, com, tuple(tuple(row) for row in inertia)  # type: ignore[return-value]


def rotated_inertia(q: Quat, inertia: Matrix3) -> Matrix3:
    """R I R^T."""
    rot = quat_matrix(q)
    return tuple(  # type: ignore[return-value]
        tuple(sum(rot[r][a] * inertia[a][b] * rot[k][b] for a in range(3) for b in range(3)) for k in range(3))
        for r in range(3)
    )
