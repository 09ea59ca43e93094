"""The camera benchmark's scene: the TurtleBot driving its circle in a furnished room, with the benchmark's RGB-D
camera (libgazebo_ros_openni_kinect.so tags) on its base, and one camera frame as the ROS adapter makes it."""
from __future__ import annotations

import os
from typing import Any, Callable, List, Optional, Tuple

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
