"""hector_gazebo_plugins' service types must be wire-compatible with tu-darmstadt-ros-pkg's
(github.com/tu-darmstadt-ros-pkg/hector_gazebo, commit de947fb, hector_gazebo_plugins/srv): a client built against
the real package calls our IMU's set_accel_bias and our GPS's set_reference_geopose.

UPSTREAM: the md5sums genmsg computes from the upstream .srv files (GeoPose from geographic_msgs 0.5.6).
"""
import sys
from pathlib import Path

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(PACKAGE_ROOT.parent / "workspace_testing" / "src"))
from workspace_testing.msg_md5 import md5_tests  # noqa: E402

UPSTREAM = {
    "srv/SetBias": "af1f260075d9ba9bd73ca10c6a45df07",
    "srv/SetReferenceGeoPose": "fe903ca95d0210defda73a1629604439",
}

globals().update(
    md5_tests(
        PACKAGE_ROOT, "hector_gazebo_plugins", ["std_msgs", "geometry_msgs"], UPSTREAM, siblings=["geographic_msgs"]
    )
)
