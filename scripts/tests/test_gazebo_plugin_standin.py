"""Gazebo plugins in robot packages, built over the gazebo stand-in (catkin_ws/src/gazebo_ros/cmake/
gazebo-standin-plugins.cmake.in): a library whose sources include Gazebo's headers, directly or through one of the
package's headers, is built as an empty shared library of the same name; every other library compiles as written.
Packages are written by us in the style of ETH's smb_gazebo (ETHZ-RobotX/smb_common, smb_gazebo/CMakeLists.txt: a
ModelPlugin library odometry_source_plugin from src/OdometrySource.cpp, whose header include/smb_gazebo/
OdometrySource.hpp includes gazebo/physics/physics.hh; add_dependencies, target_link_libraries without keyword,
install(TARGETS)); smb_gazebo itself is built from $SMB_COMMON (a checkout or a git mirror of smb_common) when set.

Scratch workspaces in a temp folder, built over our devel space (catkin_ws/devel, built by scripts/build.sh)."""
import os
import shutil
import subprocess

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from test_find_package_gazebo import DEVEL, MANIFEST, catkin_make, needs_devel_space, write_package

STATUS = "gazebo stand-in: library %s built empty"
NOT_SIMULATED = "turtle_sim_ode does not simulate lib%s.so"
SIMULATED = "turtle_sim_ode simulates lib%s.so"

# A ModelPlugin in smb_gazebo's style (ours): the header includes Gazebo's, the source includes the header
PLUGIN_HEADER = """#pragma once
#include <ros/ros.h>
#include <gazebo/common/Plugin.hh>
#include <gazebo/physics/physics.hh>

namespace gazebo {
class PoseSource : public ModelPlugin {
 public:
  void Load(physics::ModelPtr model, sdf::ElementPtr sdf) override;

 private:
  physics::ModelPtr model_;
};
}  // namespace gazebo
"""
PLUGIN_SOURCE = """#include "scratch_plugins/PoseSource.hpp"

namespace gazebo {
void PoseSource::Load(physics::ModelPtr model, sdf::ElementPtr) { model_ = model; }
GZ_REGISTER_MODEL_PLUGIN(PoseSource)
}  // namespace gazebo
"""
WHEEL_MATH_HEADER = """#pragma once
#include <gazebo_msgs/ModelState.h>

namespace scratch_plugins {
double wheelSpeed(double linear, double radius);
}
"""
WHEEL_MATH_SOURCE = """#include "scratch_plugins/wheel_math.hpp"

namespace scratch_plugins {
double wheelSpeed(double linear, double radius) { return linear / radius; }
}  // namespace scratch_plugins
"""
NODE_SOURCE = """#include <ros/ros.h>
#include "scratch_plugins/wheel_math.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "wheel_node");
  ROS_INFO("wheel speed [%f]", scratch_plugins::wheelSpeed(0.5, 0.1));
  return 0;
}
"""
PLUGINS_CMAKELISTS = """cmake_minimum_required(VERSION 3.0.2)
project(scratch_plugins)
set(CMAKE_CXX_FLAGS "-std=c++17 -Wall -Wextra")
find_package(catkin REQUIRED COMPONENTS gazebo_ros gazebo_msgs roscpp)
find_package(gazebo REQUIRED)
include_directories(include ${GAZEBO_INCLUDE_DIRS} ${catkin_INCLUDE_DIRS})
link_directories(${GAZEBO_LIBRARY_DIRS})
catkin_package(INCLUDE_DIRS include LIBRARIES pose_source_plugin wheel_math CATKIN_DEPENDS gazebo_ros roscpp)
add_library(pose_source_plugin src/PoseSource.cpp)
add_dependencies(pose_source_plugin ${catkin_EXPORTED_TARGETS})
target_link_libraries(pose_source_plugin ${catkin_LIBRARIES} ${GAZEBO_LIBRARIES})
set_target_properties(pose_source_plugin PROPERTIES VERSION 0.0.1)
add_library(wheel_math src/wheel_math.cpp)
target_link_libraries(wheel_math ${catkin_LIBRARIES})
add_executable(wheel_node src/wheel_node.cpp)
target_link_libraries(wheel_node wheel_math pose_source_plugin ${catkin_LIBRARIES})
install(TARGETS pose_source_plugin wheel_math wheel_node
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
"""
# A second package of the same workspace that finds gazebo too (its own MODULE plugin, the simulated diff drive's
# file name): the stand-in is read twice in one CMake run
SECOND_CMAKELISTS = """cmake_minimum_required(VERSION 3.0.2)
project(scratch_second)
find_package(catkin REQUIRED COMPONENTS gazebo_ros)
find_package(gazebo REQUIRED)
catkin_package()
add_library(gazebo_ros_diff_drive MODULE src/drive.cpp)
add_library(second_math src/second_math.cpp)
"""
SECOND_PLUGIN = """#include <gazebo/gazebo.hh>
namespace gazebo { class Drive : public ModelPlugin {}; }
"""
SECOND_MATH = "int secondMathAnswer() { return 42; }\n"


def manifest(name, depends):
    return MANIFEST.format(name=name, depends="".join("<depend>%s</depend>" % depend for depend in depends))


def dynamic_symbols(library):
    result = subprocess.run(["nm", "-D", "-C", "--defined-only", library], stdout=subprocess.PIPE, check=True)
    return result.stdout.decode()


def test_a_package_with_a_gazebo_plugin_builds_beside_a_second_one(tmp_path):
    needs_devel_space()
    src = str(tmp_path / "src")
    write_package(
        src,
        "scratch_plugins",
        {
            "package.xml": manifest("scratch_plugins", ("gazebo_ros", "gazebo_msgs", "roscpp")),
            "CMakeLists.txt": PLUGINS_CMAKELISTS,
            "include/scratch_plugins/PoseSource.hpp": PLUGIN_HEADER,
            "include/scratch_plugins/wheel_math.hpp": WHEEL_MATH_HEADER,
            "src/PoseSource.cpp": PLUGIN_SOURCE,
            "src/wheel_math.cpp": WHEEL_MATH_SOURCE,
            "src/wheel_node.cpp": NODE_SOURCE,
        },
    )
    write_package(
        src,
        "scratch_second",
        {
            "package.xml": manifest("scratch_second", ("gazebo_ros",)),
            "CMakeLists.txt": SECOND_CMAKELISTS,
            "src/drive.cpp": SECOND_PLUGIN,
            "src/second_math.cpp": SECOND_MATH,
        },
    )
    code, output = catkin_make(str(tmp_path))
    assert code == 0, output[-5000:]
    lib = tmp_path / "devel" / "lib"
    assert (lib / "libpose_source_plugin.so").read_bytes()[:4] == b"\x7fELF"
    assert (lib / "libgazebo_ros_diff_drive.so").read_bytes()[:4] == b"\x7fELF"
    assert "scratch_plugins::wheelSpeed(double, double)" in dynamic_symbols(str(lib / "libwheel_math.so"))
    assert "secondMathAnswer()" in dynamic_symbols(str(lib / "libsecond_math.so"))
    assert "PoseSource" not in dynamic_symbols(str(lib / "libpose_source_plugin.so"))
    assert os.access(str(lib / "scratch_plugins" / "wheel_node"), os.X_OK)
    # install(TARGETS) of the plugin holds too
    installed = subprocess.run(
        ["make", "-C", str(tmp_path / "build"), "install"],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        universal_newlines=True,
    )
    assert installed.returncode == 0, installed.stdout[-3000:]
    assert (tmp_path / "install" / "lib" / "libpose_source_plugin.so").exists()
    assert (tmp_path / "install" / "lib" / "scratch_plugins" / "wheel_node").exists()
    # one line per plugin, naming the target, the file that brings Gazebo in, and what the simulator does with it
    lines = [line for line in output.splitlines() if "gazebo stand-in: library" in line]
    assert len(lines) == 2, "\n".join(lines)
    pose = next(line for line in lines if STATUS % "pose_source_plugin" in line)
    assert "src/PoseSource.cpp includes include/scratch_plugins/PoseSource.hpp" in pose
    assert "<gazebo/common/Plugin.hh>" in pose and NOT_SIMULATED % "pose_source_plugin" in pose
    drive = next(line for line in lines if STATUS % "gazebo_ros_diff_drive" in line)
    assert "src/drive.cpp includes <gazebo/gazebo.hh>" in drive and SIMULATED % "gazebo_ros_diff_drive" in drive


# A plain CMake project (no catkin) that finds the stand-in, for many configure runs in one build folder
PROBE_CMAKELISTS = """cmake_minimum_required(VERSION 3.0.2)
project(probe CXX)
find_package(gazebo REQUIRED)
find_package(gazebo REQUIRED)
add_library({target} src/probe.cpp)
get_target_property(probe_sources {target} SOURCES)
message(STATUS "probe sources: ${{probe_sources}}")
"""


class Probe:
    """One build folder configured again for each case (compiler checks done once)."""

    def __init__(self, root):
        self.source = os.path.join(root, "probe")
        self.build = os.path.join(root, "build")
        os.makedirs(self.build, exist_ok=True)

    def configure(self, files, target="probe_plugin"):
        """(intercepted, output) for a package of these files (relative path -> text) adding library target."""
        shutil.rmtree(self.source, ignore_errors=True)
        files = dict(files, **{"CMakeLists.txt": PROBE_CMAKELISTS.format(target=target)})
        for path, text in files.items():
            full = os.path.join(self.source, path)
            os.makedirs(os.path.dirname(full), exist_ok=True)
            with open(full, "w") as out:
                out.write(text)
        result = subprocess.run(
            ["cmake", "-Wno-dev", "-DCMAKE_PREFIX_PATH=" + DEVEL, self.source],
            cwd=self.build,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            universal_newlines=True,
        )
        assert result.returncode == 0, result.stdout[-3000:]
        sources = [line for line in result.stdout.splitlines() if "probe sources: " in line]
        assert len(sources) == 1, result.stdout[-3000:]
        return "gazebo_standin/%s.cpp" % target in sources[0], result.stdout


@pytest.fixture(scope="module")
def probe(tmp_path_factory):
    needs_devel_space()
    return Probe(str(tmp_path_factory.mktemp("probe")))


@pytest.mark.parametrize(
    "files,intercepted",
    [
        ({"src/probe.cpp": "#include <gazebo/gazebo.hh>\n"}, True),
        ({"src/probe.cpp": '#include "gazebo/physics/physics.hh"\n'}, True),
        ({"src/probe.cpp": '#include "probe.hpp"\n', "src/probe.hpp": "#include <gazebo/common/Plugin.hh>\n"}, True),
        (
            {"src/probe.cpp": "#include <probe/p.hpp>\n", "include/probe/p.hpp": "  #  include<gazebo/gazebo.hh>\n"},
            True,
        ),
        ({"src/probe.cpp": "#include <gazebo_msgs/ModelState.h>\n#include <my_gazebo/gazebo.hh>\n"}, False),
        ({"src/probe.cpp": "// #include <gazebo/gazebo.hh>\nint probe();\n"}, False),
        # one level deep only: a header of the package's header is not read
        (
            {
                "src/probe.cpp": '#include "a.hpp"\n',
                "src/a.hpp": '#include "b.hpp"\n',
                "src/b.hpp": "#include <gazebo/gazebo.hh>\n",
            },
            False,
        ),
    ],
)
def test_which_libraries_are_intercepted_hand_picked(probe, files, intercepted):
    assert probe.configure(files)[0] is intercepted


@pytest.mark.parametrize(
    "target,simulated", [("gazebo_ros_p3d", True), ("gazebo_ros_imu_sensor", True), ("my_own_plugin", False)]
)
def test_the_line_says_whether_the_simulator_simulates_the_plugin(probe, target, simulated):
    intercepted, output = probe.configure({"src/probe.cpp": "#include <gazebo/gazebo.hh>\n"}, target)
    assert intercepted
    lines = [line for line in output.splitlines() if STATUS % target in line]
    assert len(lines) == 1, output[-3000:]
    assert "src/probe.cpp includes <gazebo/gazebo.hh>" in lines[0]
    assert ((SIMULATED if simulated else NOT_SIMULATED) % target) in lines[0]


SPACE = st.sampled_from(["", " ", "\t", "  "])
GAZEBO_HEADERS = st.sampled_from(["gazebo/gazebo.hh", "gazebo/physics/physics.hh", "gazebo/common/Plugin.hh"])
# look like Gazebo's but are not: ROS message packages, other packages, a commented-out include, Gazebo's own
# header named without its folder
DECOYS = st.sampled_from(
    [
        "#include <gazebo_msgs/ModelStates.h>",
        '#include "gazebo_plugins/PubQueue.h"',
        "#include <my_gazebo/gazebo/x.hh>",
        "#include <ros/ros.h>",
        "// #include <gazebo/gazebo.hh>",
        "#include <gazebo.hh>",
        "#include <sdf/sdf.hh>",
        "int gazebo_value = 1;",
    ]
)


@st.composite
def include_lines(draw, header):
    before, after_hash, after_include = draw(SPACE), draw(SPACE), draw(SPACE)
    opening, closing = draw(st.sampled_from([("<", ">"), ('"', '"')]))
    return "%s#%sinclude%s%s%s%s" % (before, after_hash, after_include, opening, header, closing)


@settings(max_examples=30, deadline=None)
@given(
    uses_gazebo=st.booleans(),
    where=st.sampled_from(["source", "header in include/", "header beside the source"]),
    decoys=st.lists(DECOYS, max_size=4),
    data=st.data(),
)
def test_which_libraries_are_intercepted_generated(probe, uses_gazebo, where, decoys, data):
    """Intercepted exactly when a gazebo/ header is included by the source or by a header of the package it
    includes; the decoys never count, wherever they are."""
    gazebo_line = [data.draw(include_lines(data.draw(GAZEBO_HEADERS)))] if uses_gazebo else []
    lines = data.draw(st.permutations(decoys + gazebo_line))
    if where == "source":
        files = {"src/probe.cpp": "\n".join(lines) + "\n"}
    else:
        folder, name = ("include/", "probe/probe.hpp") if where == "header in include/" else ("src/", "probe.hpp")
        files = {"src/probe.cpp": data.draw(include_lines(name)) + "\n", folder + name: "\n".join(lines) + "\n"}
    intercepted, output = probe.configure(files)
    assert intercepted is uses_gazebo, files
    assert (STATUS % "probe_plugin" in output) is uses_gazebo


def smb_common():
    location = os.environ.get("SMB_COMMON", "")
    if not location:
        pytest.skip("SMB_COMMON is not set (a checkout or git mirror of ETHZ-RobotX/smb_common)")
    if not os.path.isdir(location):
        pytest.skip("SMB_COMMON=%s: no such directory" % location)
    return location


def copy_upstream_package(location, package, destination):
    """package's folder of a checkout, or of HEAD of a git mirror, into destination."""
    if os.path.isdir(os.path.join(location, package)):
        shutil.copytree(os.path.join(location, package), os.path.join(destination, package))
        return
    archive = subprocess.run(["git", "--git-dir", location, "archive", "HEAD", package], stdout=subprocess.PIPE)
    assert archive.returncode == 0, "%s has no %s at HEAD" % (location, package)
    subprocess.run(["tar", "-x", "-C", destination], input=archive.stdout, check=True)


def test_smb_gazebo_of_the_course_builds_unchanged(tmp_path):
    """ETH's smb_gazebo as the course ships it: its odometry_source_plugin (src/OdometrySource.cpp, through
    include/smb_gazebo/OdometrySource.hpp) is built empty, the package's catkin_package(LIBRARIES ...), links and
    install(TARGETS) hold, and the line says the simulator simulates libodometry_source_plugin.so."""
    location = smb_common()
    needs_devel_space()
    (tmp_path / "src").mkdir()
    copy_upstream_package(location, "smb_gazebo", str(tmp_path / "src"))
    code, output = catkin_make(str(tmp_path))
    assert code == 0, output[-5000:]
    assert (tmp_path / "devel" / "lib" / "libodometry_source_plugin.so").read_bytes()[:4] == b"\x7fELF"
    lines = [line for line in output.splitlines() if STATUS % "odometry_source_plugin" in line]
    assert len(lines) == 1, output[-5000:]
    assert "src/OdometrySource.cpp includes include/smb_gazebo/OdometrySource.hpp" in lines[0]
    assert "<gazebo/physics/physics.hh>" in lines[0]
    # turtle_sim_ode does the plugin's work (world/plugins/odometry_source.py)
    assert SIMULATED % "odometry_source_plugin" in lines[0]
