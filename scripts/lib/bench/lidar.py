#!/usr/bin/env python3
"""What a 3D lidar costs the simulation (issue #23): the TurtleBot driving its circle at 1 ms steps in
bench.camera's furnished room, stepped without a lidar and with a VLP-16 (velodyne_description's VLP-16 macro: 16
lasers x 1800 samples, 10 Hz, libgazebo_ros_velodyne_laser.so) on its base, each scan cast and its cloud packed as
the ROS adapter does (sockets aside): on the lidar's thread, beside the stepping (sensors.scan_thread).

``lidar_cost`` returns a dict for bench_sim's JSON; run alone (``python3 -m bench.lidar``
in scripts/lib; ``--quick`` for a shorter run) it prints the table, the load and the CPU time the host stole meanwhile.
Real-time factors are the best of ``repeats`` timed runs taken in turns; the figure that matters is the share of
the real-time factor without a lidar that is kept with it. Beside it, the share of the stepping thread's CPU time
without a lidar over that with it (best runs each): what a lidar still costs the stepping thread itself, which the
load of a busy machine moves less than the wall time.
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

from bench.camera import MODEL, PACKAGE, best_seconds, stepper, turtlebot_in_room
from ros_run.process_stats import cpu_ticks

# (horizontal samples, lasers, rate Hz): the VLP-16 of the issue first.
LIDARS: Tuple[Tuple[int, int, float], ...] = ((1800, 16, 10.0), (1024, 64, 10.0))
LIDAR_BLOCK = """
  <gazebo reference="base_link">
    <sensor type="ray" name="bench_lidar">
      <pose>0 0 0.5 0 0 0</pose>
      <update_rate>{rate}</update_rate>
      <ray>
        <scan>
          <horizontal><samples>{samples}</samples><resolution>1</resolution>
            <min_angle>-3.14159265</min_angle><max_angle>3.14159265</max_angle></horizontal>
          <vertical><samples>{lasers}</samples><resolution>1</resolution>
            <min_angle>-0.2617994</min_angle><max_angle>0.2617994</max_angle></vertical>
        </scan>
        <range><min>0.3</min><max>131</max><resolution>0.001</resolution></range>
      </ray>
      <plugin name="velodyne" filename="libgazebo_ros_velodyne_laser.so">
        <topicName>/velodyne_points</topicName><frameName>velodyne</frameName>
        <min_range>0.9</min_range><max_range>130.0</max_range><gaussianNoise>0.008</gaussianNoise>
      </plugin>
    </sensor>
  </gazebo>
</robot>"""


def lidar_scans(sim: Any, ray_kernel: bool = True) -> Any:
    """Scans as VelodynePublisher makes them while subscribed (VelodyneScans): the geometry taken at the step, then
    on the lidar's thread the rays, the cloud and the message's bytes."""
    import numpy as np

    from turtle_sim_ode.ros.camera_topics import packer
    from turtle_sim_ode.ros.plugins.velodyne import POINT_FIELDS
    from turtle_sim_ode.sensors.lidar import MultiBeamLidar
    from turtle_sim_ode.sensors.plugins.velodyne import POINT_STEP, VelodyneConfig, VelodyneScans
    from turtle_sim_ode.sensors.scan_thread import cpus_beside_stepping
    from sensor_msgs.msg import PointCloud2

    (config,) = [c for c in sim.plugins[MODEL].configs if isinstance(c, VelodyneConfig)]
    lidar = MultiBeamLidar(
        sim.physics, sim.models[MODEL], config, ray_kernel=ray_kernel, threads=cpus_beside_stepping()
    )
    if ray_kernel and not lidar.uses_ray_kernel:
        raise RuntimeError("libturtle_sim_ode_rays.so is not built: run scripts/build.sh")
    message = PointCloud2(fields=POINT_FIELDS, point_step=POINT_STEP)
    pack = packer(message)

    def sink(points: Any, height: int, width: int, dense: bool, stamp: Tuple[int, int]) -> None:
        message.height, message.width, message.row_step = height, width, POINT_STEP * width
        pack(1, *stamp, points, dense)

    return VelodyneScans(lidar, np.random.default_rng(1), sink)


def scan_and_wait(scans: Any) -> Callable[[], None]:
    """One scan, start to end: what it would cost the stepping thread if it were made there."""

    def work() -> None:
        scans.scan((0, 0))
        scans.wait()

    return work


def with_lidar(lidar: Tuple[int, int, float]) -> Tuple[Any, Any]:
    samples, lasers, rate = lidar
    sim, _ = turtlebot_in_room(None, LIDAR_BLOCK.format(samples=samples, lasers=lasers, rate=rate))
    return sim, lidar_scans(sim)


def scanning_stepper(sim: Any, scans: Any, rate: float) -> Callable[[int], None]:
    """bench.camera's stepper starting a scan whenever one is due; a run ends when its last scan is made."""
    run = stepper(sim, [lambda: scans.scan((0, 0))], rate)

    def run_and_wait(steps: int) -> None:
        run(steps)
        scans.wait()

    return run_and_wait


def thread_cpu_timed(run: Callable[[int], None], steps: int, cpu: List[float]) -> Callable[[], None]:
    """``run(steps)``, its stepping thread's CPU time appended to ``cpu``."""

    def work() -> None:
        start = time.thread_time()
        run(steps)
        cpu.append(time.thread_time() - start)

    return work


def lidar_cost(
    steps: int = 3000, repeats: int = 3, lidars: Sequence[Tuple[int, int, float]] = LIDARS
) -> Dict[str, Any]:
    """Real-time factors at 1 ms steps without and with each lidar, their ratios, and the time a scan takes."""
    bare = turtlebot_in_room(None)
    worlds = [with_lidar(lidar) for lidar in lidars]
    numpy_scans = [lidar_scans(sim, ray_kernel=False) for sim, _ in worlds]
    try:
        runs = [stepper(*bare, 0.0)]
        runs += [scanning_stepper(sim, scans, lidar[2]) for (sim, scans), lidar in zip(worlds, lidars)]
        cpu: List[List[float]] = [[] for _ in runs]
        best = best_seconds([thread_cpu_timed(run, steps, seconds) for run, seconds in zip(runs, cpu)], repeats)
        time_step = bare[0].physics.time_step
        rtf = [steps * time_step / seconds for seconds in best]
        rows = []
        for index, ((samples, lasers, rate), (_, scans)) in enumerate(zip(lidars, worlds)):
            whole_scans = [scan_and_wait(scans), scan_and_wait(numpy_scans[index])]
            scan_best, numpy_best = best_seconds(whole_scans, max(3, repeats))
            rows.append(
                {
                    "samples": samples,
                    "lasers": lasers,
                    "rate_hz": rate,
                    "rtf": rtf[index + 1],
                    "rtf_share": rtf[index + 1] / rtf[0],
                    "stepping_cpu_share": min(cpu[0]) / min(cpu[index + 1]),
                    "ms_per_scan": scan_best * 1e3,
                    "ms_per_scan_numpy": numpy_best * 1e3,
                }
            )
    finally:
        for scans in [scans for _, scans in worlds] + numpy_scans:
            scans.close()
    return {"time_step": time_step, "rtf_without_lidar": rtf[0], "lidars": rows}


def table(result: Dict[str, Any]) -> str:
    lines = [
        "| lidar | rate | RTF | share of RTF without lidar | share of stepping thread CPU | ms / scan (C rays) "
        "| ms / scan (numpy rays) |",
        "|---|---|---|---|---|---|---|",
        f"| none | - | {result['rtf_without_lidar']:.2f} | 1.00 | 1.00 | - | - |",
    ]
    for row in result["lidars"]:
        lines.append(
            f"| {row['lasers']} x {row['samples']} rays | {row['rate_hz']:g} Hz | {row['rtf']:.2f} | "
            f"{row['rtf_share']:.2f} | {row['stepping_cpu_share']:.2f} | {row['ms_per_scan']:.1f} | "
            f"{row['ms_per_scan_numpy']:.1f} |"
        )
    return "\n".join(lines)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="1 s of sim time per run, 2 repeats")
    args = parser.parse_args(argv)
    sys.path.insert(0, os.path.join(PACKAGE, "src"))
    ticks = cpu_ticks()
    print(table(lidar_cost(1000, 2) if args.quick else lidar_cost()))
    all_ticks, stolen = (end - start for end, start in zip(cpu_ticks(), ticks))
    print(
        "load %.2f on %d cores; CPU stolen by the host meanwhile: %.1f %%"
        % (os.getloadavg()[0], os.cpu_count() or 0, 100 * stolen / max(all_ticks, 1))
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
