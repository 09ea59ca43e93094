"""kobuki_gazebo_plugins (``libgazebo_ros_kobuki.so``): a differential drive with the Kobuki's topics under the model's
name (as turtlebot_gazebo has them), its gyro, bumpers and cliff sensors (sensors.kobuki)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Tuple

from turtle_sim_ode.models.text import robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.sensors.kobuki import KOBUKI_CLIFF_THRESHOLD
from turtle_sim_ode.world.diff_drive import DiffDriveParams
from turtle_sim_ode.world.plugins.diff_drive import DriveConfig
from turtle_sim_ode.world.plugins.tags import flag, number, text

KOBUKI = "libgazebo_ros_kobuki.so"
MODEL_PLUGINS = (KOBUKI,)


# The <sensor> names kobuki_description gives the plugin (GazeboRosKobuki::Load reads them from these tags).
CLIFF_SENSORS = ("cliff_sensor_left", "cliff_sensor_front", "cliff_sensor_right")
BUMPER_SENSOR = "bumpers"
IMU_SENSOR = "imu"
WHEEL_DROP_SENSORS = ("wheel_drop_left", "wheel_drop_right")


@dataclass
class KobukiConfig(DriveConfig):
    cliff_threshold: float = KOBUKI_CLIFF_THRESHOLD  # the Kobuki's cliff sensors (m to the floor)
    # The model's <sensor>s the plugin uses, by name: cliff rays (left, center, right), the bumpers' contact sensor,
    # the gyro, the wheel drops' contact sensors (left, right). Where a model has none of that name, the simulator
    # falls back on kobuki_description's geometry (sensors.kobuki).
    cliff_sensors: Tuple[str, str, str] = CLIFF_SENSORS
    bumper_sensor: str = BUMPER_SENSOR
    imu_sensor: str = IMU_SENSOR
    wheel_drop_sensors: Tuple[str, str] = WHEEL_DROP_SENSORS


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> KobukiConfig:
    """The Kobuki's tags; ``overrides`` are the node's ~diff_drive parameters."""
    return KobukiConfig(
        filename=plugin.filename,
        left_joint=text(plugin, "left_wheel_joint_name", "wheel_left_joint"),
        right_joint=text(plugin, "right_wheel_joint_name", "wheel_right_joint"),
        params=DiffDriveParams.from_kobuki_plugin(plugin.params, **overrides),
        command_topic=model_name + "/commands/velocity",
        reset_topic=model_name + "/commands/reset_odometry",
        odometry_topic="odom",
        odometry_frame="",
        base_frame="",
        odometry_source="encoder",
        publish_tf=flag(plugin, "publish_tf", True),
        publish_joint_states=True,
        update_rate=0.0,
        robot_namespace=robot_namespace_tag(plugin.params),
        cliff_threshold=number(plugin, "cliff_detection_threshold", KOBUKI_CLIFF_THRESHOLD, minimum=1e-6),
        cliff_sensors=(
            text(plugin, "cliff_sensor_left_name", CLIFF_SENSORS[0]),
            text(plugin, "cliff_sensor_center_name", CLIFF_SENSORS[1]),
            text(plugin, "cliff_sensor_right_name", CLIFF_SENSORS[2]),
        ),
        bumper_sensor=text(plugin, "bumper_name", BUMPER_SENSOR),
        imu_sensor=text(plugin, "imu_name", IMU_SENSOR),
        wheel_drop_sensors=(
            text(plugin, "wheel_drop_left_sensor_name", WHEEL_DROP_SENSORS[0]),
            text(plugin, "wheel_drop_right_sensor_name", WHEEL_DROP_SENSORS[1]),
        ),
    )
