"""libgazebo_ros_multicamera.so in a multicamera sensor: as GazeboRosMultiCamera::Load, the camera whose name holds
"left" under cameraName/left with no baseline, "right" under cameraName/right with hackBaseline
(gazebo_plugins/src/gazebo_ros_multicamera.cpp), each posed on the sensor's pose."""
from __future__ import annotations

import pytest

from turtle_sim_ode.sensors.config import read_sdf_sensors
from turtle_sim_ode.sensors.plugins.multicamera import MultiCameraConfig

# A stereo head as multisense / stereo_camera descriptions write it: two cameras 0.07 m apart.
STEREO_SDF = """<sdf version="1.6"><model name="head"><static>true</static><link name="head_link">
  <sensor type="multicamera" name="stereo_camera"><update_rate>20</update_rate><pose>0.1 0 0.2 0 0 0</pose>
    <camera name="left"><horizontal_fov>1.0</horizontal_fov><image><width>16</width><height>12</height></image>
      <clip><near>0.05</near><far>20</far></clip></camera>
    <camera name="right"><pose>0 -0.07 0 0 0 0</pose><horizontal_fov>1.0</horizontal_fov>
      <image><width>16</width><height>12</height></image><clip><near>0.05</near><far>20</far></clip></camera>
    <plugin name="stereo_camera_controller" filename="libgazebo_ros_multicamera.so">
      <cameraName>stereo</cameraName><imageTopicName>image_raw</imageTopicName>
      <cameraInfoTopicName>camera_info</cameraInfoTopicName><frameName>left_optical</frameName>
      <hackBaseline>0.07</hackBaseline></plugin>
  </sensor></link></model></sdf>"""


def test_left_and_right_cameras() -> None:
    (config,) = read_sdf_sensors(STEREO_SDF).configs
    assert isinstance(config, MultiCameraConfig)
    left, right = config.cameras
    assert (left.camera_name, right.camera_name) == ("stereo/left", "stereo/right")
    assert (left.hack_baseline, right.hack_baseline) == (0.0, 0.07)
    assert left.update_rate == right.update_rate == 20.0  # one schedule: identical stamps
    assert left.pose == pytest.approx((0.1, 0.0, 0.2, 0.0, 0.0, 0.0))
    assert right.pose == pytest.approx((0.1, -0.07, 0.2, 0.0, 0.0, 0.0))
    assert left.frame == right.frame == "left_optical" and (left.width, left.height) == (16, 12)
