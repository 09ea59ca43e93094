"""SDF text for the tests of the plugins that read a grid of rays (block laser, range finder): a static model whose one
link, 0.5 m up, carries a ray sensor of horizontal x vertical rays and the plugin, as gazebo_plugins' test worlds
write them."""
from __future__ import annotations

from typing import Tuple

Scan = Tuple[int, float, float]  # samples, min_angle, max_angle


def _scan(axis: str, samples: int, low: float, high: float) -> str:
    return (
        f"<{axis}><samples>{samples}</samples><resolution>1</resolution><min_angle>{low}</min_angle>"
        f"<max_angle>{high}</max_angle></{axis}>"
    )


def ray_grid_sdf(
    link: str,
    sensor: str,
    update_rate: float,
    horizontal: Scan,
    vertical: Scan,
    range_tags: str,
    plugin: str,
    tags: str,
) -> str:
    """Model "bot" with ``sensor`` on ``link``; ``range_tags``: what <range> holds; ``plugin``'s file name, and
    ``tags`` inside it."""
    return f"""<sdf version="1.6"><model name="bot"><static>true</static><link name="{link}">
  <pose>0 0 0.5 0 0 0</pose>
  <sensor type="ray" name="{sensor}"><update_rate>{update_rate}</update_rate>
    <ray><scan>{_scan("horizontal", *horizontal)}{_scan("vertical", *vertical)}</scan>
      <range>{range_tags}</range></ray>
    <plugin name="{sensor}" filename="{plugin}">{tags}</plugin>
  </sensor></link></model></sdf>"""
