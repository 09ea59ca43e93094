"""find_package(gazebo) where Gazebo is not installed: the gazebo_ros drop-in writes gazebo's CMake package as
turtle_sim_ode's stand-in (catkin_ws/src/gazebo_ros/cmake), so packages written as ROBOTIS' turtlebot3_gazebo is
(turtlebot3_simulations noetic-devel, turtlebot3_gazebo/CMakeLists.txt: find_package(gazebo REQUIRED),
catkin_package(DEPENDS GAZEBO), turtlebot3_drive linking ${GAZEBO_LIBRARIES}) build over this workspace; where a
real Gazebo's package config exists the drop-in writes none.

Scratch workspaces in a temp folder, built over our devel space (catkin_ws/devel, built by scripts/build.sh)."""
import os
import shutil
import subprocess
import tempfile

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DEVEL = os.path.join(REPO, "catkin_ws", "devel")
GAZEBO_ROS = os.path.join(REPO, "catkin_ws", "src", "gazebo_ros")
STANDIN = os.path.join(DEVEL, "share", "gazebo", "cmake")
STANDIN_VERSION = (11, 15, 1)
STANDIN_NOTE = "turtle_sim_ode's stand-in"

MANIFEST = """<?xml version="1.0"?>
<package format="2">
  <name>{name}</name>
  <version>0.0.1</version>
  <description>scratch package in turtlebot3_gazebo's style</description>
  <maintainer email="dev@example.com">m</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  {depends}
</package>
"""
# As turtlebot3_gazebo's CMakeLists.txt uses gazebo (written by us in its style)
CMAKELISTS = """cmake_minimum_required(VERSION 3.0.2)
project(scratch_gazebo)
find_package(catkin REQUIRED COMPONENTS roscpp geometry_msgs tf urdf gazebo_ros)
find_package(gazebo REQUIRED)
catkin_package(CATKIN_DEPENDS roscpp geometry_msgs tf gazebo_ros DEPENDS GAZEBO)
link_directories(${GAZEBO_LIBRARY_DIRS})
include_directories(${catkin_INCLUDE_DIRS} ${GAZEBO_INCLUDE_DIRS})
set(CMAKE_CXX_FLAGS "${CMAKE_CXX_FLAGS} ${GAZEBO_CXX_FLAGS}")
add_executable(scratch_drive src/scratch_drive.cpp)
target_link_libraries(scratch_drive ${catkin_LIBRARIES} ${GAZEBO_LIBRARIES})
"""
NODE = """#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "scratch_drive");
  ros::NodeHandle node;
  ros::Publisher cmd_vel = node.advertise<geometry_msgs::Twist>("cmd_vel", 1);
  cmd_vel.publish(geometry_msgs::Twist());
  return 0;
}
"""
# A real Gazebo's package config, as libgazebo-dev installs it (its content does not matter to the drop-in)
REAL_CONFIG = 'set(GAZEBO_FOUND TRUE)\nset(GAZEBO_VERSION "11.10.2")\n'


def needs_devel_space():
    if not shutil.which("catkin_make") or not shutil.which("cmake"):
        pytest.skip("catkin_make or cmake not on PATH")
    if not os.path.isfile(os.path.join(STANDIN, "gazebo-config.cmake")):
        pytest.skip("no stand-in in %s: run scripts/build.sh" % STANDIN)


def catkin_make(workspace, first_prefix=None, timeout=300):
    """catkin_make in workspace over our devel space, first_prefix (if given) ahead on CMAKE_PREFIX_PATH (setup.bash
    sets CMAKE_PREFIX_PATH, so it goes in after); (return code, output)."""
    prefix = 'export CMAKE_PREFIX_PATH="%s:$CMAKE_PREFIX_PATH" && ' % first_prefix if first_prefix else ""
    command = '. "%s/setup.bash" && %scatkin_make -C "%s" -DCATKIN_ENABLE_TESTING=0' % (DEVEL, prefix, workspace)
    result = subprocess.run(
        ["bash", "-c", command],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        universal_newlines=True,
        timeout=timeout,
    )
    return result.returncode, result.stdout


def write_package(src, name, files):
    for path, text in files.items():
        full = os.path.join(src, name, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "w") as out:
            out.write(text)


def test_a_turtlebot3_gazebo_style_package_builds(tmp_path):
    needs_devel_space()
    depends = "".join("<depend>%s</depend>" % name for name in ("roscpp", "geometry_msgs", "tf", "urdf", "gazebo_ros"))
    files = {
        "package.xml": MANIFEST.format(name="scratch_gazebo", depends=depends),
        "CMakeLists.txt": CMAKELISTS,
        "src/scratch_drive.cpp": NODE,
    }
    write_package(str(tmp_path / "src"), "scratch_gazebo", files)
    code, output = catkin_make(str(tmp_path))
    assert code == 0, output[-5000:]
    assert "gazebo 11.15.1: " + STANDIN_NOTE in output
    assert os.access(str(tmp_path / "devel" / "lib" / "scratch_gazebo" / "scratch_drive"), os.X_OK)


@pytest.mark.parametrize("real_gazebo", [False, True])
def test_the_drop_in_stands_aside_for_a_real_gazebo(tmp_path, real_gazebo):
    """gazebo_ros configured in a scratch workspace of its own: it writes the stand-in into that devel space unless
    a real Gazebo's config is under a prefix on CMAKE_PREFIX_PATH (lib/<arch>/cmake/gazebo, as Ubuntu has it)."""
    needs_devel_space()
    os.makedirs(str(tmp_path / "ws" / "src"))
    shutil.copytree(GAZEBO_ROS, str(tmp_path / "ws" / "src" / "gazebo_ros"), ignore=shutil.ignore_patterns("test"))
    real_prefix = None
    if real_gazebo:
        real_prefix = tmp_path / "gazebo_prefix"
        (real_prefix / "lib" / "cmake" / "gazebo").mkdir(parents=True)
        (real_prefix / "lib" / "cmake" / "gazebo" / "gazebo-config.cmake").write_text(REAL_CONFIG)
    code, output = catkin_make(str(tmp_path / "ws"), real_prefix)
    assert code == 0, output[-5000:]
    written = (tmp_path / "ws" / "devel" / "share" / "gazebo" / "cmake" / "gazebo-config.cmake").exists()
    assert written is not real_gazebo, output[-5000:]
    assert ("Gazebo's own CMake package" in output) is real_gazebo


def version_check(requested):
    """(compatible, exact) as find_package(gazebo <requested>) reads them from the stand-in's version file."""
    script = 'set(PACKAGE_FIND_VERSION "%s")\n' % ".".join(map(str, requested))
    for index, name in enumerate(("MAJOR", "MINOR", "PATCH")):
        value = requested[index] if index < len(requested) else 0
        script += 'set(PACKAGE_FIND_VERSION_%s "%d")\n' % (name, value)
    script += 'include("%s/gazebo-config-version.cmake")\n' % STANDIN
    script += 'message("${PACKAGE_VERSION_COMPATIBLE} ${PACKAGE_VERSION_EXACT}")\n'
    with tempfile.NamedTemporaryFile("w", suffix=".cmake") as script_file:
        script_file.write(script)
        script_file.flush()
        result = subprocess.run(
            ["cmake", "-P", script_file.name], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True
        )
    assert result.returncode == 0, result.stdout
    compatible, exact = (result.stdout.strip() + " ").split(" ", 1)
    return compatible == "TRUE", exact.strip() == "TRUE"


@pytest.mark.parametrize(
    "requested,compatible,exact",
    [
        ((11,), True, False),
        ((11, 0), True, False),
        ((11, 15, 1), True, True),
        ((11, 16), False, False),
        ((9,), False, False),
        ((12,), False, False),
    ],
)
def test_version_file_hand_picked(requested, compatible, exact):
    needs_devel_space()
    assert version_check(requested) == (compatible, exact)


@settings(max_examples=25, deadline=None)
@given(
    st.builds(
        lambda major, rest: [major] + rest,
        st.sampled_from([10, 11, 12]) | st.integers(min_value=0, max_value=30),
        st.lists(st.integers(min_value=0, max_value=30), max_size=2),
    )
)
def test_version_file_generated(requested):
    """Compatible exactly when the major version is 11 and the request is not newer than 11.15.1 (CMake's
    SameMajorVersion rule, as gazebo's own version file has it)."""
    needs_devel_space()
    padded = tuple(requested) + (0,) * (3 - len(requested))
    compatible, exact = version_check(tuple(requested))
    assert compatible == (padded[0] == 11 and padded <= STANDIN_VERSION)
    assert exact == (padded == STANDIN_VERSION)
