#!/usr/bin/env python3
"""Measure what a model costs the simulator (issue #16), without ROS: the real-time factor flat out of a chain of
N links (N - 1 revolute joints, box collisions, lying on the ground) on its own, and the wall time of one laser
scan of R rays, under which the node holds the world lock. Run by hand: numbers for the README's cost table.

    python3 test/measure_model_cost.py [--links 1 100 300 999] [--rays 360 5000 20000]
"""
import argparse
import time

from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.sensors.config import LaserConfig
from turtle_sim_ode.sensors.laser import LaserScanner
from turtle_sim_ode.world.simulation import Simulation

BOX = (
    '<link name="l{i}"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4"/></inertial>'
    "{collision}</link>"
)
COLLISION = '<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision>'

JOINT = (
    '<joint name="j{i}" type="revolute"><parent link="l{p}"/><child link="l{i}"/><origin xyz="0.06 0 0"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
)


def chain(links: int, collisions: bool = True) -> str:
    box = BOX.replace("{collision}", COLLISION if collisions else "")
    parts = [box.format(i=0)] + [box.format(i=i) + JOINT.format(i=i, p=i - 1) for i in range(1, links)]
    return '<robot name="chain">%s</robot>' % "".join(parts)


def chain_rtf(links: int, sim_seconds: float, collisions: bool) -> float:
    sim = Simulation(contact_kernel=True)
    sim.spawn_model("chain", parse_urdf(chain(links, collisions)), (0, 0, 0.03, 0, 0, 0))
    for _ in range(200):  # settle on the ground
        sim.step()
    steps = int(sim_seconds / sim.physics.time_step)
    start = time.perf_counter()
    for _ in range(steps):
        sim.step()
    return steps * sim.physics.time_step / (time.perf_counter() - start)


WALL = (
    '<robot name="wall"><link name="wall"><inertial><mass value="100"/><inertia ixx="10" iyy="10" izz="10"/>'
    '</inertial><collision><geometry><box size="4 0.1 0.5"/></geometry></collision></link></robot>'
)


def scan_seconds(rays: int, scans: int = 5) -> float:
    """Worst case: the scanner in a closed 4 m room, every beam hits a wall."""
    sim = Simulation()
    for i, (x, y, yaw) in enumerate(((2, 0, 1.5708), (-2, 0, 1.5708), (0, 2, 0), (0, -2, 0))):
        sim.spawn_model("wall_%d" % i, parse_urdf(WALL), (x, y, 0.25, 0, 0, yaw))
    sim.spawn_model("scanner", parse_urdf(chain(1)), (0, 0, 0.03, 0, 0, 0))
    scanner = LaserScanner(sim.physics, sim.models["scanner"], "l0", LaserConfig("l0", samples=rays))
    start = time.perf_counter()
    for _ in range(scans):
        scanner.scan()
    return (time.perf_counter() - start) / scans


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--links", type=int, nargs="*", default=[1, 100, 300, 1000])
    parser.add_argument("--rays", type=int, nargs="*", default=[360, 5000, 20000])
    parser.add_argument("--sim-seconds", type=float, default=1.0)
    args = parser.parse_args()
    for links in args.links:
        for collisions in (False, True):
            rtf = chain_rtf(links, args.sim_seconds, collisions)
            kind = "box collisions on the ground" if collisions else "no collisions, falling"
            print("chain of %4d links (%4d joints), %s: real-time factor %.2f" % (links, links - 1, kind, rtf))
    for rays in args.rays:
        seconds = scan_seconds(rays)
        print("laser of %6d rays, every beam hitting a wall: %.1f ms per scan (world locked)" % (rays, seconds * 1e3))


if __name__ == "__main__":
    main()
