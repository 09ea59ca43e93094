"""ROS-free plotting of recorded planar paths (matplotlib, no display needed)."""
from __future__ import annotations

from typing import Dict, List, Sequence, Tuple

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

Path2D = Sequence[Tuple[float, float]]


def plot_paths(paths: Dict[str, Path2D], output: str, title: str = "") -> str:
    """Draw each labelled path (x, y in metres) with equal axes, mark the start, and write a PNG to `output`."""
    figure, axes = plt.subplots(figsize=(6, 6), dpi=100)
    for label, path in paths.items():
        if not path:
            continue
        xs: List[float] = [p[0] for p in path]
        ys: List[float] = [p[1] for p in path]
        axes.plot(xs, ys, label=label, linewidth=1.5)
    first = next((p for p in paths.values() if p), None)
    if first:
        axes.plot(first[0][0], first[0][1], "ko", label="start")
    axes.set_aspect("equal", adjustable="datalim")
    axes.set_xlabel("x [m]")
    axes.set_ylabel("y [m]")
    axes.grid(True, alpha=0.3)
    axes.legend(loc="best")
    if title:
        axes.set_title(title)
    figure.tight_layout()
    figure.savefig(output)
    plt.close(figure)
    return output
