#!/usr/bin/env python3
"""What a camera costs the simulation: the TurtleBot driving its circle at 1 ms steps in a furnished room, stepped
without a camera and with an RGB-D camera (libgazebo_ros_openni_kinect.so tags) on its base rendering colour, depth
and the organised cloud and packing them as the ROS adapter does (sockets aside) at its rate in sim time.

``camera_cost`` returns a dict for bench_sim's JSON; run alone (``python3 -m bench.camera``
in scripts/lib; ``--quick`` for a shorter run) it prints the table.
Real-time factors are the best of ``repeats`` timed runs, taken in turns so that each sees the same machine load;
the figure that matters is the ratio with / without camera of one run.
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

from bench import camera_peers
from bench.camera_scene import CAMERAS, MODEL, PACKAGE, TARGET_SHARE, frame_work, turtlebot_in_room


def stepper(sim: Any, frames: Sequence[Callable[[], None]], rate: float) -> Callable[[int], None]:
    """Steps ``sim`` n times, making a frame whenever one is due in sim time."""
    period = 1.0 / rate if rate else 0.0
    due = [sim.sim_time]

    def run(steps: int) -> None:
        for _ in range(steps):
            sim.step()
            if frames and sim.sim_time >= due[0] - 1e-9:
                due[0] += period
                for frame in frames:
                    frame()

    return run


def best_seconds(works: Sequence[Callable[[], None]], repeats: int) -> List[float]:
    """The best wall time of each of ``works`` over ``repeats`` rounds, run in turns so each sees the same load."""
    best = [float("inf")] * len(works)
    for _ in range(repeats):
        for index, work in enumerate(works):
            start = time.perf_counter()
            work()
            best[index] = min(best[index], time.perf_counter() - start)
    return best


def camera_cost(
    steps: int = 3000, repeats: int = 3, cameras: Sequence[Tuple[int, int, float]] = CAMERAS
) -> Dict[str, Any]:
    """Real-time factors at 1 ms steps without and with each camera (best of ``repeats`` runs of ``steps``), their
    ratios, and the time one frame takes (render + packing)."""
    runs = [stepper(*turtlebot_in_room(None), 0.0)]
    worlds = [turtlebot_in_room(camera) for camera in cameras]
    runs += [stepper(sim, frames, camera[2]) for (sim, frames), camera in zip(worlds, cameras)]
    best = best_seconds([lambda run=run: run(steps) for run in runs], repeats)
    time_step = worlds[0][0].physics.time_step
    rtf = [steps * time_step / seconds for seconds in best]
    rows = []
    for index, ((width, height, rate), (sim, frames)) in enumerate(zip(cameras, worlds)):
        numpy_frame = frame_work(sim, sim.plugins[MODEL].cameras[0], ray_kernel=False)
        frame_best, numpy_best = best_seconds([frames[0], numpy_frame], max(3, repeats))
        rows.append(
            {
                "width": width,
                "height": height,
                "rate_hz": rate,
                "rtf": rtf[index + 1],
                "rtf_share": rtf[index + 1] / rtf[0],
                "ms_per_frame": frame_best * 1e3,
                "ms_per_frame_numpy": numpy_best * 1e3,
            }
        )
    target = next((row for row in rows if (row["width"], row["height"], row["rate_hz"]) == CAMERAS[0]), None)
    return {
        "time_step": time_step,
        "renderer": "rays in C (src/ray_kernel.c); ms_per_frame_numpy: the numpy fallback (sensors.raycast)",
        "rtf_without_camera": rtf[0],
        "cameras": rows,
        "target_share": TARGET_SHARE,
        "target_met": None if target is None else target["rtf_share"] >= TARGET_SHARE,
    }


def table(result: Dict[str, Any]) -> str:
    lines = [
        "| camera | rate | RTF | share of RTF without camera | ms / frame (C rays) | ms / frame (numpy rays) |",
        "|---|---|---|---|---|---|",
        f"| none | - | {result['rtf_without_camera']:.2f} | 1.00 | - | - |",
    ]
    for row in result["cameras"]:
        lines.append(
            f"| {row['width']}x{row['height']} RGB-D | {row['rate_hz']:g} Hz | {row['rtf']:.2f} | "
            f"{row['rtf_share']:.2f} | {row['ms_per_frame']:.1f} | {row['ms_per_frame_numpy']:.1f} |"
        )
    lines.append(f"target: 320x240 at 15 Hz keeps >= {result['target_share']:.0%}: {result['target_met']}")
    return "\n".join(lines)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="1 s of sim time per run, 2 repeats")
    parser.add_argument(
        "--peers", action="store_true", help="also pyrender and Open3D on the same frames (camera_peers)"
    )
    parser.add_argument(
        "--peer-threads", type=int, default=1, help="threads of every renderer, ours too (0: each one's default)"
    )
    parser.add_argument("--peers-json", help="write the peers' figures to this file")
    args = parser.parse_args(argv)
    sys.path.insert(0, os.path.join(PACKAGE, "src"))
    result = camera_cost(1000, 2) if args.quick else camera_cost()
    print(table(result))
    if args.peers:
        peers = (
            camera_peers.compare(4, 2, args.peer_threads)
            if args.quick
            else camera_peers.compare(8, 3, args.peer_threads)
        )
        print(camera_peers.table(peers))
        if args.peers_json:
            with open(args.peers_json, "w") as out:
                json.dump(peers, out, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
