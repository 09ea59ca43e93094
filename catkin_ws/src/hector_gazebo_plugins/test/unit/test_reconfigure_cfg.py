"""hector_gazebo_plugins' dynamic_reconfigure types must show clients the parameters of tu-darmstadt-ros-pkg's
(github.com/tu-darmstadt-ros-pkg/hector_gazebo, melodic-devel, hector_gazebo_plugins/cfg): the same names, types,
defaults, bounds and levels, as generated from our cfg/SensorModel.cfg and cfg/GNSS.cfg (the workspace sourced)."""
from hector_gazebo_plugins.cfg import GNSSConfig, SensorModelConfig

# name: (type, default, min, max, level), from upstream's cfg/SensorModel.cfg and cfg/GNSS.cfg.
SENSOR_MODEL = {
    "gaussian_noise": ("double", 0.0, 0.0, 10.0, 1),
    "offset": ("double", 0.0, -10.0, 10.0, 1),
    "drift": ("double", 0.0, 0.0, 10.0, 1),
    "drift_frequency": ("double", 0.0, 0.0, 1.0, 1),
    "scale_error": ("double", 1.0, 0.0, 2.0, 1),
}
GNSS = {
    "STATUS_FIX": ("bool", True, False, True, 1),
    "STATUS_SBAS_FIX": ("bool", False, False, True, 1),
    "STATUS_GBAS_FIX": ("bool", False, False, True, 1),
    "SERVICE_GPS": ("bool", True, False, True, 1),
    "SERVICE_GLONASS": ("bool", True, False, True, 1),
    "SERVICE_COMPASS": ("bool", True, False, True, 1),
    "SERVICE_GALILEO": ("bool", True, False, True, 1),
}


def described(config_type) -> dict:  # type: ignore[no-untyped-def]
    return {
        p["name"]: (p["type"], p["default"], p["min"], p["max"], p["level"])
        for p in config_type.config_description["parameters"]
    }


def test_sensor_model_config_is_upstream_s() -> None:
    assert described(SensorModelConfig) == SENSOR_MODEL


def test_gnss_config_is_upstream_s() -> None:
    assert described(GNSSConfig) == GNSS
    assert list(described(GNSSConfig)) == list(GNSS)  # upstream's order, as rqt_reconfigure lists them
