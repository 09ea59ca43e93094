"""ros.resource_paths (issue #31): a package.xml on ROS_PACKAGE_PATH that catkin_pkg refuses (InvalidPackage:
catkin_pkg/package.py Package.validate's version and email rules, a missing license) is skipped with one
warning naming it; the simulator reads every other package and its gazebo_model_path export."""
from __future__ import annotations

from pathlib import Path
from typing import List

import hypothesis.strategies as st
from hypothesis import HealthCheck, given, settings

from turtle_sim_ode.ros.resource_paths import resource_paths

GOOD = """<?xml version="1.0"?>
<package format="2">
  <name>{name}</name><version>1.0.0</version><description>d</description>
  <maintainer email="me@example.com">me</maintainer><license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <export><gazebo_ros gazebo_model_path="${{prefix}}/models"/></export>
</package>
"""


def write_package(root: Path, name: str, text: str) -> Path:
    folder = root / name
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(text)
    return folder


def read(root: Path) -> "tuple":
    warnings: List[str] = []
    paths = resource_paths({"ROS_PACKAGE_PATH": str(root)}, warnings.append)
    return paths, warnings


def test_a_package_catkin_pkg_refuses_is_skipped_with_one_warning(tmp_path: Path) -> None:
    good = write_package(tmp_path, "good_pkg", GOOD.format(name="good_pkg"))
    # catkin_pkg Package.validate: a version must be three dot-separated integers, an email must look like one
    write_package(tmp_path, "bad_version", GOOD.format(name="bad_version").replace("1.0.0", "1.0"))
    paths, warnings = read(tmp_path)
    assert paths.packages == {"good_pkg": str(good)}
    assert str(good / "models") in paths.model_paths
    assert len(warnings) == 1 and "'bad_version'" in warnings[0] and "version" in warnings[0]


def test_a_package_without_a_license_is_skipped_too(tmp_path: Path) -> None:
    """catkin_pkg/package.py parse_package_string: at least one <license> tag, else InvalidPackage."""
    write_package(tmp_path, "good_pkg", GOOD.format(name="good_pkg"))
    write_package(tmp_path, "no_license", GOOD.format(name="no_license").replace("<license>BSD</license>", ""))
    paths, warnings = read(tmp_path)
    assert list(paths.packages) == ["good_pkg"]
    assert len(warnings) == 1 and "'no_license'" in warnings[0] and "license" in warnings[0]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    version=st.text(alphabet="0123456789.-a", min_size=0, max_size=8),
    email=st.sampled_from(["me@example.com", "a@b.c", "", "nobody"]),
)
def test_generated_manifests_never_stop_the_reading(tmp_path: Path, version: str, email: str) -> None:
    """Whatever the version and email: the package is read or skipped with exactly one warning naming it."""
    root = tmp_path / f"r{abs(hash((version, email)))}"
    text = GOOD.format(name="odd_pkg").replace("1.0.0", version).replace("me@example.com", email)
    write_package(root, "odd_pkg", text)
    write_package(root, "good_pkg", GOOD.format(name="good_pkg"))
    paths, warnings = read(root)
    assert "good_pkg" in paths.packages
    if "odd_pkg" in paths.packages:
        assert warnings == []
    else:
        assert len(warnings) == 1 and "'odd_pkg'" in warnings[0]
