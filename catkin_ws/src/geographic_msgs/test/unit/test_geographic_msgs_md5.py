"""geographic_msgs must be wire-compatible with ros-geographic-info's (github.com/ros-geographic-info/geographic_info,
master at bc73c05, release 0.5.6, geographic_msgs/{msg,srv}): a node built against the real package (a GPS
client calling hector's set_reference_geopose, a route planner) talks to ours.

UPSTREAM: the md5sums genmsg computes from the upstream package's own .msg/.srv files, with uuid_msgs' UniqueID
from ros-geographic-info/unique_identifier 1.0.6.
"""
import sys
from pathlib import Path

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(PACKAGE_ROOT.parent / "workspace_testing" / "src"))
from workspace_testing.msg_md5 import md5_tests  # noqa: E402

UPSTREAM = {
    "msg/BoundingBox": "f62e8b5e390a3ac7603250d46e8f8446",
    "msg/GeoPath": "1476008e63041203a89257cfad97308f",
    "msg/GeoPoint": "c48027a852aeff972be80478ff38e81a",
    "msg/GeoPointStamped": "ea50d268b03080563c330351a21edc89",
    "msg/GeoPose": "778680b5172de58b7c057d973576c784",
    "msg/GeoPoseStamped": "cc409c8ed6064d8a846fa207bf3fba6b",
    "msg/GeoPoseWithCovariance": "84c133e7220362d3d8aff8e415075357",
    "msg/GeoPoseWithCovarianceStamped": "2cc818b24aae5ffa4fd33f5ee0bb5421",
    "msg/GeographicMap": "0f4ce6d2ebf9ac9c7c4f3308f6ae0731",
    "msg/GeographicMapChanges": "4fd027f54298203ec12aa1c4b20e6cb8",
    "msg/KeyValue": "cf57fdc6617a881a88c16e768132149c",
    "msg/MapFeature": "e2505ace5e8da8a15b610eaf62bdefae",
    "msg/RouteNetwork": "fd717c0a34a7c954deed32c6847f30a8",
    "msg/RoutePath": "0aa2dd809a8091bdb4466dfefecbb8cf",
    "msg/RouteSegment": "8583d1e2ddf1891c3934a5d2ed9a799c",
    "msg/WayPoint": "ef04f823aef332455a49eaec3f1761b7",
    "srv/GetGeoPath": "ee0dbd181711a70f823cc5d415fa609b",
    "srv/GetGeographicMap": "c0278e653eee0ad79600510650e7be39",
    "srv/GetRoutePlan": "04479050c4f2a58d915ceec419e70b4e",
    "srv/UpdateGeographicMap": "93db3f1ec099e9f1b7e442d7d397e244",
}

globals().update(
    md5_tests(PACKAGE_ROOT, "geographic_msgs", ["std_msgs", "geometry_msgs"], UPSTREAM, siblings=["uuid_msgs"])
)
