#!/usr/bin/env python3
"""What a camera costs the simulation: the TurtleBot driving its circle at 1 ms steps in a furnished room, stepped
without a camera and with an RGB-D camera (libgazebo_ros_openni_kinect.so tags) on its base rendering colour, depth
and the organised cloud and packing them as the ROS adapter does (sockets aside) at its rate in sim time.

``camera_cost`` returns a dict for bench_sim's JSON; run alone (``python3 -m bench.camera``
in scripts/lib; ``--quick`` for a shorter run) it prints the table; ``python3 -m bench.camera_peers`` compares the
renderers issue #15 names on its frames.
Real-time factors are the best of ``repeats`` timed runs, taken in turns so that each sees the same machine load;
the figure that matters is the ratio with / without camera of one run.
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

PACKAGE = os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "catkin_ws", "src", "turtle_sim_ode"
)
URDF_PATH = os.path.join(PACKAGE, "urdf", "turtlebot.urdf")
MODEL = "mobile_base"
CIRCLE = (0.5, 0.5)  # v (m/s), w (rad/s), as bench_sim drives it
# (width, height, rate Hz): the target row first.
CAMERAS: Tuple[Tuple[int, int, float], ...] = ((320, 240, 15.0), (640, 480, 30.0))
TARGET_SHARE = 0.30  # a 320x240 camera at 15 Hz keeps at least this share of the real-time factor
CAMERA_BLOCK = """
  <gazebo reference="{link}">
    <sensor type="depth" name="bench_camera">
      <update_rate>{rate}</update_rate>
      <pose>0.1 0 0.4 0 0 0</pose>
      <camera>
        <horizontal_fov>1.047</horizontal_fov>
        <image><width>{width}</width><height>{height}</height><format>R8G8B8</format></image>
        <clip><near>0.05</near><far>20</far></clip>
      </camera>
      <plugin name="camera_controller" filename="libgazebo_ros_openni_kinect.so">
        <cameraName>camera</cameraName>
        <imageTopicName>rgb/image_raw</imageTopicName>
        <cameraInfoTopicName>rgb/camera_info</cameraInfoTopicName>
        <depthImageTopicName>depth/image_raw</depthImageTopicName>
        <depthImageCameraInfoTopicName>depth/camera_info</depthImageCameraInfoTopicName>
        <pointCloudTopicName>depth/points</pointCloudTopicName>
        <frameName>camera_rgb_optical_frame</frameName>
        <pointCloudCutoff>0.3</pointCloudCutoff>
        <pointCloudCutoffMax>8.0</pointCloudCutoffMax>
      </plugin>
    </sensor>
  </gazebo>
</robot>"""
# A 6 m x 6 m room: four walls and five coloured boxes and cylinders about the robot's circle.
ROOM_SDF = """<sdf version="1.6"><model name="room"><static>true</static>{links}</model></sdf>"""
ROOM_PARTS = [
    ("wall_n", "box", "6 0.1 1", (0, 3, 0.5), "Gazebo/Grey"),
    ("wall_s", "box", "6 0.1 1", (0, -3, 0.5), "Gazebo/Grey"),
    ("wall_e", "box", "0.1 6 1", (3, 0, 0.5), "Gazebo/Wood"),
    ("wall_w", "box", "0.1 6 1", (-3, 0, 0.5), "Gazebo/Wood"),
    ("box_1", "box", "0.4 0.4 0.4", (2, 1, 0.2), "Gazebo/Red"),
    ("box_2", "box", "0.3 0.6 0.5", (-1.5, 2, 0.25), "Gazebo/Blue"),
    ("box_3", "box", "0.5 0.5 0.3", (1.5, -2, 0.15), "Gazebo/Green"),
    ("pillar_1", "cylinder", "", (-2, -1.5, 0.5), "Gazebo/Yellow"),
    ("ball_1", "sphere", "", (0.5, 2.2, 0.3), "Gazebo/Orange"),
]


# The camera's topics (relative to the robot's namespace) that carry renderings, by kind.
CAMERA_TOPICS = {"image": "camera/rgb/image_raw", "depth": "camera/depth/image_raw", "points": "camera/depth/points"}


def with_camera(urdf: str, camera: Tuple[int, int, float], link: str = "base_link") -> str:
    """``urdf`` with the benchmark's RGB-D camera, (width, height, rate Hz), on ``link``."""
    width, height, rate = camera
    return urdf.replace("</robot>", CAMERA_BLOCK.format(link=link, width=width, height=height, rate=rate))


def room_sdf() -> str:
    links = []
    for name, shape, size, (x, y, z), material in ROOM_PARTS:
        geometry = {
            "box": f"<box><size>{size}</size></box>",
            "cylinder": "<cylinder><radius>0.2</radius><length>1.0</length></cylinder>",
            "sphere": "<sphere><radius>0.3</radius></sphere>",
        }[shape]
        links.append(
            f'<link name="{name}"><pose>{x} {y} {z} 0 0 0</pose>'
            f'<collision name="c"><geometry>{geometry}</geometry></collision>'
            f'<visual name="v"><geometry>{geometry}</geometry>'
            f"<material><script><name>{material}</name></script></material></visual></link>"
        )
    return ROOM_SDF.format(links="".join(links))


def turtlebot_in_room(
    camera: Optional[Tuple[int, int, float]], sensor_block: str = ""
) -> Tuple[Any, List[Callable[[], None]]]:
    """The Simulation and, with ``camera`` (width, height, rate), one renderer-and-packer per camera;
    ``sensor_block``: URDF text that replaces the robot's closing tag (another sensor, bench_lidar's)."""
    from turtle_sim_ode.world.simulation import Simulation

    with open(URDF_PATH) as urdf_file:
        urdf = urdf_file.read()
    if camera is not None:
        urdf = with_camera(urdf, camera)
    if sensor_block:
        urdf = urdf.replace("</robot>", sensor_block)
    sim = Simulation()
    sim.spawn_urdf(MODEL, urdf, (0.0, -1.0, 0.0, 0.0, 0.0, 0.0))
    sim.spawn_sdf("room", room_sdf())
    robot = sim.robots[MODEL]
    robot.params.cmd_timeout = 0.0
    robot.drive.set_command(CIRCLE[0], CIRCLE[1], sim.sim_time)
    return sim, [frame_work(sim, config) for config in sim.plugins[MODEL].cameras]


def frame_work(sim: Any, config: Any, ray_kernel: bool = True) -> Callable[[], None]:
    """One frame as CameraPublisher makes it with every topic subscribed: render, then the image, depth image and
    cloud packed into their messages' bytes (what the node writes to the sockets); ``ray_kernel`` False: the rays
    and the cloud in numpy."""
    from turtle_sim_ode.ros.camera_topics import colour_image, packer, templates
    from turtle_sim_ode.sensors.camera import CameraSensor

    sensor = CameraSensor(sim.physics, sim.models[MODEL], config, ray_kernel=ray_kernel)
    if ray_kernel and not sensor.uses_ray_kernel:
        raise RuntimeError("libturtle_sim_ode_rays.so is not built: run scripts/build.sh")
    messages = templates(sensor)
    pack_image, pack_depth, pack_cloud = (packer(messages[key]) for key in ("image", "depth", "points"))

    def work() -> None:
        frame = sensor.render(sim.scene)
        pack_image(1, 0, 0, colour_image(frame.rgb, config.encoding))
        depth, cloud, dense = sensor.organised_cloud(frame)
        pack_depth(1, 0, 0, depth)
        pack_cloud(1, 0, 0, cloud, dense)

    return work


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
        "renderer": "rays in C (src/ray_camera.c); ms_per_frame_numpy: the numpy fallback (sensors.raycast)",
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
    args = parser.parse_args(argv)
    sys.path.insert(0, os.path.join(PACKAGE, "src"))
    result = camera_cost(1000, 2) if args.quick else camera_cost()
    print(table(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
