"""Node depthimage_to_laserscan: sensor_msgs/Image `image` (+ its camera_info) -> sensor_msgs/LaserScan `scan`.

As ros-perception/depthimage_to_laserscan's node: private params scan_height, scan_time, range_min, range_max,
output_frame_id; the image is subscribed only while `scan` has subscribers; its camera_info is the image topic's
sibling `camera_info`, as image_transport's camera subscriber finds it.
"""
from __future__ import annotations

import threading
from typing import Optional

import rospy
from sensor_msgs.msg import CameraInfo, Image, LaserScan

from depthimage_to_laserscan.convert import ConversionError, convert, depth_array

# name: (default, minimum, maximum) as upstream's cfg/Depth.cfg has them
NUMBER_PARAMS = {
    "scan_time": (0.033, 0.0, 1.0),
    "range_min": (0.45, 0.0, 10.0),
    "range_max": (10.0, 0.0, 10.0),
}
SCAN_HEIGHT = (1, 1, 500)


class ParamError(ValueError):
    pass


def read_params() -> dict:
    params = {}
    for name, (default, low, high) in NUMBER_PARAMS.items():
        value = rospy.get_param("~" + name, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not low <= value <= high:
            raise ParamError("~%s must be a number in [%g, %g], got [%r]" % (name, low, high, value))
        params[name] = float(value)
    height = rospy.get_param("~scan_height", SCAN_HEIGHT[0])
    if isinstance(height, bool) or not isinstance(height, int) or not SCAN_HEIGHT[1] <= height <= SCAN_HEIGHT[2]:
        raise ParamError("~scan_height must be an integer in [1, 500], got [%r]" % (height,))
    params["scan_height"] = height
    params["output_frame_id"] = str(rospy.get_param("~output_frame_id", "camera_depth_frame"))
    if params["range_min"] > params["range_max"]:
        raise ParamError("~range_min [%g] is above ~range_max [%g]" % (params["range_min"], params["range_max"]))
    return params


class DepthToScan(rospy.SubscribeListener):
    def __init__(self, params: dict) -> None:
        super().__init__()
        self._params = params
        self._lock = threading.Lock()
        self._info: Optional[CameraInfo] = None
        self._subs = []
        self._pub = rospy.Publisher("scan", LaserScan, queue_size=10, subscriber_listener=self)

    def peer_subscribe(self, topic_name, topic_publish, peer_publish) -> None:
        with self._lock:
            if not self._subs:
                image = rospy.resolve_name("image")
                info = image.rsplit("/", 1)[0] + "/camera_info"
                self._subs = [
                    rospy.Subscriber(info, CameraInfo, self._on_info, queue_size=1),
                    rospy.Subscriber(image, Image, self._on_image, queue_size=1, buff_size=2**24),
                ]

    def peer_unsubscribe(self, topic_name, num_peers) -> None:
        with self._lock:
            if num_peers == 0:
                for sub in self._subs:
                    sub.unregister()
                self._subs = []

    def _on_info(self, info: CameraInfo) -> None:
        self._info = info

    def _on_image(self, image: Image) -> None:
        info = self._info
        if info is None:
            rospy.logwarn_throttle(
                5.0, "depthimage_to_laserscan: no camera_info yet for %s", rospy.resolve_name("image")
            )
            return
        p = self._params
        try:
            depth = depth_array(image.data, image.encoding, image.width, image.height, image.step, image.is_bigendian)
            scan = convert(depth, info.K[0], info.K[2], info.K[5], p["scan_height"], p["range_min"], p["range_max"])
        except ConversionError as error:
            rospy.logerr_throttle(1.0, "Could not convert depth image to laserscan: %s", error)
            return
        msg = LaserScan()
        msg.header = image.header
        if p["output_frame_id"]:
            msg.header.frame_id = p["output_frame_id"]
        msg.angle_min, msg.angle_max, msg.angle_increment = scan.angle_min, scan.angle_max, scan.angle_increment
        msg.scan_time = p["scan_time"]
        msg.range_min, msg.range_max = p["range_min"], p["range_max"]
        msg.ranges = scan.ranges.tolist()
        self._pub.publish(msg)


def main() -> int:
    rospy.init_node("depthimage_to_laserscan")
    try:
        DepthToScan(read_params())
    except ParamError as error:
        rospy.logfatal("depthimage_to_laserscan: %s", error)
        return 1
    rospy.spin()  # returns at shutdown; it raises no ROSInterruptException (rospy/client.py, spin)
    return 0
