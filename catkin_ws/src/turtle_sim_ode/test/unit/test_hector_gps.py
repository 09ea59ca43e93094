"""libhector_gazebo_ros_gps.so: tags and defaults as GazeboRosGps::Load reads them, and Update's fix
(hector_gazebo_plugins/src/gazebo_ros_gps.cpp): WGS84 radii at the reference latitude, latitude from the position
turned by the reference heading, the world's <spherical_coordinates> with useWorldSphericalCoordinates, and a new
reference through setGeoposeCb; the dynamic_reconfigure servers' effects: the GNSS flags of dynamicReconfigureCallback
and the covariance of a reconfigured error model."""
from __future__ import annotations

import math
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from turtle_sim_ode.models.sdf_world import parse_sdf_world
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.plugins import read_plugins
from turtle_sim_ode.world.plugins.hector_gps import GNSS_FLAGS as FLAGS
from turtle_sim_ode.world.plugins.hector_gps import HECTOR_GPS, HectorGps
from turtle_sim_ode.world.plugins.hector_sensor_model import reconfigure
from turtle_sim_ode.world.simulation import Simulation

POST_SDF = """<sdf version="1.6"><model name="post"><static>true</static><link name="gps_link">
  <collision name="c"><geometry><box><size>0.1 0.1 0.1</size></box></geometry></collision></link></model></sdf>"""
A, F = 6378137.0, 1.0 / 298.257223563  # WGS84, as the plugin's constants


def radii(latitude_deg: float) -> tuple:
    e2 = 2 * F - F * F
    s = math.sin(math.radians(latitude_deg))
    temp = 1.0 / (1.0 - e2 * s * s)
    prime = A * math.sqrt(temp)
    return prime * (1 - e2) * temp, prime * math.cos(math.radians(latitude_deg))


def gps(params: dict, spherical=None) -> HectorGps:  # type: ignore[no-untyped-def]
    sim = Simulation()
    sim.spawn_sdf("post", POST_SDF, (100.0, 50.0, 2.0, 0, 0, 0))
    (config,) = read_plugins("post", [GazeboPlugin(HECTOR_GPS, "gps", params)], {}, []).configs
    return HectorGps(sim.models["post"], "gps_link", config, spherical, random.Random(1))


def test_defaults() -> None:
    (config,) = read_plugins("m", [GazeboPlugin(HECTOR_GPS, "gps", {})], {}, []).configs
    # Load: /world, fix, fix_velocity, reference 49.9 N 8.9 E, heading 0, altitude 0; 4 Hz; status FIX.
    assert (config.frame, config.fix_topic, config.velocity_topic) == ("/world", "fix", "fix_velocity")
    assert (config.reference_latitude, config.reference_longitude, config.reference_heading) == (49.9, 8.9, 0.0)
    assert (config.update_rate, config.status, config.service) == (4.0, 0, 0)


def test_fix_of_a_post_100_m_north_50_m_west() -> None:
    fix = gps({}).update(0.0)
    north, east = radii(49.9)
    assert fix.latitude == pytest.approx(49.9 + 100.0 / north * 180.0 / math.pi, abs=1e-12)
    assert fix.longitude == pytest.approx(8.9 - 50.0 / east * 180.0 / math.pi, abs=1e-12)
    assert fix.altitude == pytest.approx(2.0) and fix.velocity == pytest.approx((0.0, 0.0, 0.0))


def test_world_spherical_coordinates_and_heading() -> None:
    world = parse_sdf_world(
        """<sdf version="1.6"><world name="w"><spherical_coordinates><latitude_deg>47.0</latitude_deg>
        <longitude_deg>8.5</longitude_deg><elevation>400</elevation><heading_deg>90</heading_deg>
        </spherical_coordinates></world></sdf>"""
    )
    assert world.spherical_coordinates == (47.0, 8.5, 400.0, 90.0)
    fix = gps({"useWorldSphericalCoordinates": "true"}, world.spherical_coordinates).update(0.0)
    north, east = radii(47.0)
    # heading 90 deg counter-clockwise from east in SDF: 0 clockwise from north, as above.
    assert fix.latitude == pytest.approx(47.0 + 100.0 / north * 180.0 / math.pi, abs=1e-9)
    assert fix.longitude == pytest.approx(8.5 - 50.0 / east * 180.0 / math.pi, abs=1e-9)
    assert fix.altitude == pytest.approx(402.0)


def test_noise_gives_the_covariance() -> None:
    fix = gps({"gaussianNoise": "0.5 0.5 1.0", "drift": "0.1 0.1 0.2"}).update(0.0)
    assert fix.position_covariance[0] == pytest.approx(0.26) and fix.position_covariance[8] == pytest.approx(1.04)


def test_set_reference_geopose_takes_the_yaw_as_east_and_keeps_the_load_radii() -> None:
    """setGeoposeCb: heading = pi/2 - yaw of the GeoPose's orientation (tf getEulerYPR), then Reset; radius_north_
    and radius_east_ are computed in Load only, so they stay those of 49.9 N even for a reference on the equator."""
    sensor = gps({})
    north, east = radii(49.9)
    sensor.set_reference(0.0, 10.0, 100.0, (0.0, 0.0, 0.0, 1.0))  # yaw 0: the world's x axis points east
    fix = sensor.update(0.0)
    assert fix.latitude == pytest.approx(50.0 / north * 180.0 / math.pi, abs=1e-12)  # y = 50 m north
    assert fix.longitude == pytest.approx(10.0 + 100.0 / east * 180.0 / math.pi, abs=1e-12)  # x = 100 m east
    assert fix.altitude == pytest.approx(102.0)
    half = math.radians(90.0) / 2  # yaw 90 deg: x points north again, as heading 0
    sensor.set_reference(49.9, 8.9, 0.0, (0.0, 0.0, 2.0 * math.sin(half), 2.0 * math.cos(half)))  # not unit
    fix = sensor.update(0.0)
    assert fix.latitude == pytest.approx(49.9 + 100.0 / north * 180.0 / math.pi, abs=1e-9)
    assert fix.longitude == pytest.approx(8.9 - 50.0 / east * 180.0 / math.pi, abs=1e-9)


@pytest.mark.parametrize(
    "latitude, longitude, altitude, orientation",
    [
        (math.nan, 0.0, 0.0, (0.0, 0.0, 0.0, 1.0)),
        (91.0, 0.0, 0.0, (0.0, 0.0, 0.0, 1.0)),
        (0.0, -180.5, 0.0, (0.0, 0.0, 0.0, 1.0)),
        (0.0, 0.0, math.inf, (0.0, 0.0, 0.0, 1.0)),
        (0.0, 0.0, 0.0, (0.0, 0.0, 0.0, 0.0)),
        (0.0, 0.0, 0.0, (0.0, 0.0, math.nan, 1.0)),
    ],
)
def test_a_refused_reference_keeps_the_old_one(latitude, longitude, altitude, orientation) -> None:  # type: ignore
    sensor = gps({})
    before = sensor.reference
    with pytest.raises(ValueError):
        sensor.set_reference(latitude, longitude, altitude, orientation)
    assert sensor.reference == before
    assert math.isfinite(sensor.update(0.0).latitude)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(
    latitude=st.floats(-90.0, 90.0),
    longitude=st.floats(-180.0, 180.0),
    altitude=st.floats(-1e4, 1e5),
    orientation=st.tuples(*[st.floats(-1.0, 1.0)] * 4).filter(lambda q: sum(v * v for v in q) > 1e-6),
)
def test_any_valid_reference_gives_a_finite_fix_at_its_altitude(latitude, longitude, altitude, orientation) -> None:
    sensor = gps({})
    sensor.set_reference(latitude, longitude, altitude, orientation)
    fix = sensor.update(0.0)
    assert all(math.isfinite(v) for v in (fix.latitude, fix.longitude, fix.altitude))
    assert fix.altitude == pytest.approx(altitude + 2.0)
    # The post is 112 m from the origin: at most ~0.001 degree of latitude away from the reference.
    assert abs(fix.latitude - latitude) < 0.0011


FIRST_LEVEL = ~0  # dynamic_reconfigure servers' first callback


def test_gnss_first_call_reports_the_tags() -> None:
    """GazeboRosGps::dynamicReconfigureCallback, level != 1: the flags read from the status and service bits."""
    sensor = gps({})
    assert sensor.reconfigure_status(dict.fromkeys(FLAGS, True), FIRST_LEVEL) == {
        "STATUS_FIX": True,
        "STATUS_SBAS_FIX": False,
        "STATUS_GBAS_FIX": False,
        "SERVICE_GPS": False,
        "SERVICE_GLONASS": False,
        "SERVICE_COMPASS": False,
        "SERVICE_GALILEO": False,
    }
    assert (sensor.status, sensor.service) == (0, 0)
    tagged = gps({"status": "2", "service": "5"})  # GBAS fix; GPS and COMPASS (NavSatStatus bits 1 and 4)
    flags = tagged.reconfigure_status({}, 0)
    assert [name for name in FLAGS if flags[name]] == [
        "STATUS_FIX",
        "STATUS_GBAS_FIX",
        "SERVICE_GPS",
        "SERVICE_COMPASS",
    ]


@pytest.mark.parametrize(
    "on, status, service",
    [
        (("STATUS_FIX",), 0, 0),
        (("STATUS_FIX", "STATUS_SBAS_FIX", "SERVICE_GPS", "SERVICE_GALILEO"), 1, 9),
        (("STATUS_FIX", "STATUS_SBAS_FIX", "STATUS_GBAS_FIX", "SERVICE_GLONASS"), 3, 2),
        (("STATUS_SBAS_FIX", "SERVICE_COMPASS"), -1, 4),  # no STATUS_FIX: STATUS_NO_FIX whatever the augmentation
    ],
)
def test_gnss_change_sets_the_next_fix_s_status_and_service(on, status, service) -> None:  # type: ignore
    """Level 1: STATUS_NO_FIX without STATUS_FIX, else SBAS (1) | GBAS (2); the service mask GPS 1, GLONASS 2,
    COMPASS 4, GALILEO 8 (sensor_msgs/NavSatStatus)."""
    sensor = gps({})
    sensor.reconfigure_status({name: name in on for name in FLAGS}, 1)
    fix = sensor.update(0.0)
    assert (fix.status, fix.service) == (status, service)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.fixed_dictionaries({name: st.booleans() for name in FLAGS}), st.sampled_from([1, 0, FIRST_LEVEL]))
def test_gnss_reports_what_it_set(values, level) -> None:  # type: ignore[no-untyped-def]
    """Any flags: a change is kept as the client gave it, and a later first call reads the same flags back from the
    bits, except that STATUS_NO_FIX (-1: every bit) reads as both augmentations, as upstream's bit tests read it;
    another level changes nothing."""
    sensor = gps({})
    reported = sensor.reconfigure_status(values, level)
    if level != 1:
        assert (sensor.status, sensor.service) == (0, 0)
        return
    assert reported == values
    assert sensor.status in (-1, 0, 1, 2, 3) and 0 <= sensor.service <= 15
    expected = dict(values)
    if not values["STATUS_FIX"]:
        expected.update(STATUS_SBAS_FIX=True, STATUS_GBAS_FIX=True)
    assert sensor.reconfigure_status({}, 0) == expected


def test_reconfigured_position_noise_gives_the_covariance() -> None:
    """Update fills the covariance from the position error model's members, so it follows a reconfiguration:
    drift^2 + gaussian_noise^2 on each axis, from the values set on every axis; the velocity's changes nothing."""
    sensor = gps({"gaussianNoise": "0.5 0.5 1.0", "drift": "0.1 0.1 0.2"})
    values = dict(gaussian_noise=2.0, offset=0.0, drift=0.5, drift_frequency=0.0, scale_error=1.0)
    reconfigure(sensor.position_error, values, 1)
    reconfigure(sensor.velocity_error, dict(values, gaussian_noise=7.0), 1)
    fix = sensor.update(0.0)
    assert fix.position_covariance == pytest.approx((4.25, 0, 0, 0, 4.25, 0, 0, 0, 4.25), abs=1e-12)
    assert sensor.config.position.gaussian_noise == (0.5, 0.5, 1.0)  # the tags stay as read
    sensor.reset()  # a world reset keeps the reconfigured model, as Reset does
    assert sensor.update(0.0).position_covariance[0] == pytest.approx(4.25)
