"""The drop-in mechanism (scripts/lib/dropins.py): a workspace drop-in (xacro, gazebo_ros, ...) never shadows a
real package of that name: the system's, one in the user's own workspace, or one in an underlay workspace.

A system package is simulated by a prefix of our own with share/<name>/package.xml, as /opt/ros/noetic has them
on Ubuntu; the drop-ins are copied into a workspace of their own, so that the real source tree is not touched.
The environment's ROS_PACKAGE_PATH and CMAKE_PREFIX_PATH are cleared unless a test sets them.
"""
import os
import shutil
import subprocess
import sys

import pytest
import rospkg
from catkin_pkg.packages import find_packages

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SRC = os.path.join(REPO, "catkin_ws", "src")
DROPINS = os.path.join(REPO, "scripts", "lib", "dropins.py")
MANIFEST = (
    '<package format="3"><name>%s</name><version>1.14.0</version><description>d</description>'
    '<maintainer email="dev@example.com">m</maintainer><license>BSD</license>'
    "<buildtool_depend>catkin</buildtool_depend></package>"
)


def run(*args, env=None):
    clean = {k: v for k, v in os.environ.items() if k not in ("ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH")}
    return subprocess.run(
        [sys.executable, DROPINS] + list(args),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        universal_newlines=True,
        env=dict(clean, **(env or {})),
    )


@pytest.fixture
def workspace(tmp_path):
    """tmp/ws/src with the two drop-ins and a package of the user's; tmp/system: an empty system prefix."""
    src = tmp_path / "ws" / "src"
    for name in ("xacro", "gazebo_ros"):
        shutil.copytree(
            os.path.join(SRC, name), str(src / name), ignore=shutil.ignore_patterns("test", "CATKIN_IGNORE")
        )
    (src / "user_pkg").mkdir()
    (src / "user_pkg" / "package.xml").write_text(MANIFEST % "user_pkg")
    (tmp_path / "system" / "share").mkdir(parents=True)
    return tmp_path


def install_system_package(workspace, name):
    folder = workspace / "system" / "share" / name
    folder.mkdir()
    (folder / "package.xml").write_text(MANIFEST % name)
    return folder


def apply(workspace, *extra, env=None):
    result = run(
        "apply", "--src", str(workspace / "ws" / "src"), "--prefix", str(workspace / "system"), *extra, env=env
    )
    assert result.returncode == 0, result.stderr
    return result


def test_without_system_packages_both_dropins_are_used(workspace):
    result = apply(workspace)
    src = workspace / "ws" / "src"
    assert sorted(result.stdout.split()) == [str(src / "gazebo_ros"), str(src / "xacro")]
    assert not (src / "xacro" / "CATKIN_IGNORE").exists()
    assert sorted(p.name for p in find_packages(str(src)).values()) == ["gazebo_ros", "user_pkg", "xacro"]


def test_system_package_wins_for_catkin_rospack_and_rospkg(workspace):
    system_xacro = install_system_package(workspace, "xacro")
    result = apply(workspace)
    src = workspace / "ws" / "src"
    assert result.stdout.split() == [str(src / "gazebo_ros")]
    assert "xacro: the real %s is used" % system_xacro in result.stderr
    assert (src / "xacro" / "CATKIN_IGNORE").read_text().startswith("# written by scripts/lib/dropins.py")
    # catkin_make and catkin-tools take their package list from catkin_pkg
    assert sorted(p.name for p in find_packages(str(src)).values()) == ["gazebo_ros", "user_pkg"]
    order = subprocess.run(["catkin_topological_order", str(src)], stdout=subprocess.PIPE, universal_newlines=True)
    assert "xacro" not in order.stdout and "gazebo_ros" in order.stdout
    # the workspace comes first on ROS_PACKAGE_PATH (devel/setup.bash puts it there), yet the system's is found
    package_path = "%s:%s" % (src, workspace / "system" / "share")
    env = dict(os.environ, ROS_PACKAGE_PATH=package_path)
    found = subprocess.run(["rospack", "find", "xacro"], stdout=subprocess.PIPE, universal_newlines=True, env=env)
    assert found.stdout.strip() == str(system_xacro)
    rospack = rospkg.RosPack(ros_paths=package_path.split(":"))
    assert rospack.get_path("xacro") == str(system_xacro)
    assert rospack.get_path("gazebo_ros") == str(src / "gazebo_ros")


def test_an_installed_dropin_is_not_a_system_package(workspace):
    """catkin_make install puts the drop-in's package.xml into share/: that copy must not ignore its source."""
    installed = workspace / "system" / "share" / "xacro"
    installed.mkdir()
    shutil.copy(os.path.join(SRC, "xacro", "package.xml"), str(installed / "package.xml"))
    result = apply(workspace)
    assert str(workspace / "ws" / "src" / "xacro") in result.stdout.split()
    assert not (workspace / "ws" / "src" / "xacro" / "CATKIN_IGNORE").exists()


def test_ignored_dropin_leftovers_leave_the_devel_space(workspace):
    devel = workspace / "ws" / "devel"
    for leftover in ("share/xacro/cmake", "lib/xacro", "share/gazebo_ros/cmake"):
        (devel / leftover).mkdir(parents=True)
    install_system_package(workspace, "xacro")
    apply(workspace, "--devel", str(devel))
    assert not (devel / "share" / "xacro").exists() and not (devel / "lib" / "xacro").exists()
    assert (devel / "share" / "gazebo_ros" / "cmake").is_dir()


def test_dropin_comes_back_when_the_system_package_goes(workspace):
    system_gazebo_ros = install_system_package(workspace, "gazebo_ros")
    apply(workspace)
    ignore = workspace / "ws" / "src" / "gazebo_ros" / "CATKIN_IGNORE"
    assert ignore.exists()
    shutil.rmtree(str(system_gazebo_ros))
    result = apply(workspace)
    assert not ignore.exists()
    assert str(workspace / "ws" / "src" / "gazebo_ros") in result.stdout.split()


def test_a_users_own_catkin_ignore_is_left_alone(workspace):
    ignore = workspace / "ws" / "src" / "gazebo_ros" / "CATKIN_IGNORE"
    ignore.write_text("")
    result = apply(workspace)
    assert ignore.exists()
    assert "has a CATKIN_IGNORE of its own: left alone" in result.stderr
    assert str(workspace / "ws" / "src" / "gazebo_ros") not in result.stdout.split()


def test_pypi_requirements_only_for_dropins_in_use_and_missing(workspace):
    target = workspace / "pypi"
    target.mkdir()
    args = ("pypi-missing", "--src", str(workspace / "ws" / "src"), "--prefix", str(workspace / "system"))
    requirements = str(workspace / "ws" / "src" / "xacro" / "pypi-requirements.txt")
    assert run(*args, "--target", str(target)).stdout.split() == [requirements]
    pin = [line for line in open(requirements) if line.startswith("xacro==")][0].split()[0]
    (target / ("xacro-%s.dist-info" % pin.split("==")[1])).mkdir()
    assert run(*args, "--target", str(target)).stdout.split() == []
    (target / ("xacro-%s.dist-info" % pin.split("==")[1])).rmdir()
    install_system_package(workspace, "xacro")
    assert run(*args, "--target", str(target)).stdout.split() == []


def add_package(folder, name, manifest=MANIFEST):
    folder.mkdir(parents=True)
    (folder / "package.xml").write_text(manifest % name if "%s" in manifest else manifest)
    return folder


def test_a_package_of_the_users_own_workspace_wins(workspace):
    """A user who clones the real gazebo_ros into the same src (catkin_ws/src/gazebo_ros_pkgs/gazebo_ros) gets it:
    catkin_make would otherwise stop on two packages of one name."""
    src = workspace / "ws" / "src"
    users = add_package(src / "gazebo_ros_pkgs" / "gazebo_ros", "gazebo_ros")
    result = apply(workspace)
    assert result.stdout.split() == [str(src / "xacro")]
    assert "gazebo_ros: the real %s is used" % users in result.stderr
    packages = find_packages(str(src))  # raises on duplicate names
    assert sorted((p.name, os.path.join(str(src), path)) for path, p in packages.items()) == [
        ("gazebo_ros", str(users)),
        ("user_pkg", str(src / "user_pkg")),
        ("xacro", str(src / "xacro")),
    ]
    # the user drops their copy: the drop-in comes back
    shutil.rmtree(str(users))
    assert str(src / "gazebo_ros") in apply(workspace).stdout.split()
    assert not (src / "gazebo_ros" / "CATKIN_IGNORE").exists()


def test_a_users_package_they_ignored_themselves_does_not_count(workspace):
    src = workspace / "ws" / "src"
    users = add_package(src / "old" / "xacro", "xacro")
    (users / "CATKIN_IGNORE").write_text("")
    assert str(src / "xacro") in apply(workspace).stdout.split()


def test_a_package_in_an_underlay_wins(workspace):
    """Underlays found as the devel/setup.bash of another workspace leaves them: its source space on
    ROS_PACKAGE_PATH, its devel space on CMAKE_PREFIX_PATH with a .catkin file naming the source space."""
    src = workspace / "ws" / "src"
    underlay_src = workspace / "underlay" / "src"
    add_package(underlay_src / "turtlebot_simulator" / "gazebo_ros", "gazebo_ros")
    result = apply(workspace, env={"ROS_PACKAGE_PATH": str(underlay_src)})
    assert result.stdout.split() == [str(src / "xacro")]
    (src / "gazebo_ros" / "CATKIN_IGNORE").unlink()
    devel = workspace / "underlay" / "devel"
    devel.mkdir()
    (devel / ".catkin").write_text(str(underlay_src))
    assert apply(workspace, env={"CMAKE_PREFIX_PATH": str(devel)}).stdout.split() == [str(src / "xacro")]
    assert apply(workspace, "--underlay", str(underlay_src)).stdout.split() == [str(src / "xacro")]


def test_a_dropin_in_an_underlay_or_the_workspace_itself_is_not_real(workspace):
    """Another checkout of this repository as an underlay, or this workspace's own src on ROS_PACKAGE_PATH (as its
    devel/setup.bash puts it), holds drop-ins only: they are not real packages."""
    src = workspace / "ws" / "src"
    underlay_src = workspace / "underlay" / "src"
    shutil.copytree(os.path.join(SRC, "xacro"), str(underlay_src / "xacro"), ignore=shutil.ignore_patterns("test"))
    result = apply(workspace, env={"ROS_PACKAGE_PATH": "%s:%s" % (underlay_src, src)})
    assert sorted(result.stdout.split()) == [str(src / "gazebo_ros"), str(src / "xacro")]


def resolved_packages(platform):
    """The system packages scripts/lib/resolve_deps.py asks for on ``platform``."""
    result = subprocess.run(
        [sys.executable, os.path.join(REPO, "scripts", "lib", "resolve_deps.py"), "--platform", platform],
        stdout=subprocess.PIPE,
        universal_newlines=True,
    )
    return result.stdout.split()


@pytest.mark.parametrize("platform", ["debian", "ubuntu"])
def test_resolver_installs_the_real_xacro_where_the_platform_has_it(platform):
    packages = resolved_packages(platform)
    if platform == "ubuntu":
        assert "ros-noetic-xacro" in packages
    else:
        assert "python3-pip" in packages and not any("xacro" in p for p in packages)
    # gazebo_ros is never installed: on a system without Gazebo the drop-in is the one
    assert not any("gazebo-ros" in p for p in packages)


# Packages Debian 12 lacks and the ROS apt repository has (ros-noetic-*): ros_control's, geographic_info's
# messages for hector's GPS service, robot_localization (the SMB course's EKF), media_export (rviz asks for it).
RELEASED_DROPINS = (
    "control_msgs",
    "controller_manager",
    "controller_manager_msgs",
    "geographic_msgs",
    "media_export",
    "robot_localization",
    "uuid_msgs",
)


def test_the_packages_debian_lacks_are_dropins(tmp_path):
    """Debian 12 has none of RELEASED_DROPINS; Ubuntu's ros-noetic-* ones win where installed, one by one."""
    src = tmp_path / "ws" / "src"
    for name in RELEASED_DROPINS:
        shutil.copytree(os.path.join(SRC, name), str(src / name), ignore=shutil.ignore_patterns("CATKIN_IGNORE"))
    (tmp_path / "system" / "share").mkdir(parents=True)
    assert sorted(apply(tmp_path).stdout.split()) == [str(src / name) for name in RELEASED_DROPINS]
    install_system_package(tmp_path, "control_msgs")
    install_system_package(tmp_path, "uuid_msgs")
    kept = ("controller_manager", "controller_manager_msgs", "geographic_msgs", "media_export", "robot_localization")
    expected = [str(src / name) for name in kept]
    assert apply(tmp_path).stdout.split() == expected


@pytest.mark.parametrize("platform", ["debian", "ubuntu"])
def test_resolver_installs_the_real_packages_where_the_platform_has_them(platform):
    packages = resolved_packages(platform)
    for name in RELEASED_DROPINS:
        real = "ros-noetic-" + name.replace("_", "-")
        assert (real in packages) == (platform == "ubuntu")


# Drop-ins of packages the courses start that Debian 12 lacks; Ubuntu's ros-noetic-* ones win where installed.
COURSE_DROPINS = ("joint_state_publisher_gui", "rqt_robot_steering", "teleop_twist_keyboard", "twist_mux")


@pytest.mark.parametrize("platform", ["debian", "ubuntu"])
def test_course_dropins_resolve_to_the_released_packages_on_ubuntu(platform):
    table = {}
    with open(os.path.join(REPO, "scripts", "lib", "rosdeps.tsv")) as rows:
        for line in rows:
            if line.strip() and not line.startswith("#"):
                key, debian, ubuntu = line.rstrip("\n").split("\t")
                table[key] = debian.split() if platform == "debian" or ubuntu == "=" else ubuntu
    for name in COURSE_DROPINS:
        real = "ros-noetic-" + name.replace("_", "-")
        if platform == "ubuntu":
            assert table[name] == "-", name  # the ROS apt naming rule
        else:
            assert real not in table[name] and name.replace("_", "-") not in table[name], name


JSP_GUI = "joint_state_publisher_gui"


def versioned(version):
    """MANIFEST at another version (its %s: the name)."""
    return MANIFEST.replace("1.14.0", version)


def test_an_installed_joint_state_publisher_gui_older_than_1_15_2_does_not_count(tmp_path):
    """Debian's joint_state_publisher_gui 1.15.1 crashes (QSlider.setValue with a float): the drop-in is built and
    found first, and says so; a 1.15.2 (Ubuntu's) or a copy in the user's workspace makes it stand aside."""
    src = tmp_path / "ws" / "src"
    dropin = src / JSP_GUI
    shutil.copytree(os.path.join(SRC, JSP_GUI), str(dropin), ignore=shutil.ignore_patterns("test"))
    system = add_package(tmp_path / "system" / "share" / "joint_state_publisher_gui", JSP_GUI, versioned("1.15.1"))
    result = apply(tmp_path)
    assert result.stdout.split() == [str(dropin)]
    said = "joint_state_publisher_gui: %s is version 1.15.1, which does not work" % system
    assert result.stderr.count(said) == 1
    package_path = "%s:%s" % (src, tmp_path / "system" / "share")
    assert rospkg.RosPack(ros_paths=package_path.split(":")).get_path("joint_state_publisher_gui") == str(dropin)

    (system / "package.xml").write_text(versioned("1.15.2") % JSP_GUI)
    result = apply(tmp_path)
    assert result.stdout.split() == []
    assert "the real %s is used" % system in result.stderr
    assert rospkg.RosPack(ros_paths=package_path.split(":")).get_path("joint_state_publisher_gui") == str(system)

    (system / "package.xml").write_text(versioned("1.15.1") % JSP_GUI)
    users = add_package(src / "joint_state_publisher" / JSP_GUI, JSP_GUI, versioned("1.15.1"))
    result = apply(tmp_path)
    assert result.stdout.split() == [] and "the real %s is used" % users in result.stderr


def test_a_broken_underlay_copy_does_not_count_either(tmp_path):
    src = tmp_path / "ws" / "src"
    dropin = src / JSP_GUI
    shutil.copytree(os.path.join(SRC, JSP_GUI), str(dropin), ignore=shutil.ignore_patterns("test"))
    (tmp_path / "system" / "share").mkdir(parents=True)
    underlay = add_package(tmp_path / "underlay" / "src" / "jsp" / JSP_GUI, JSP_GUI, versioned("1.12.13"))
    assert apply(tmp_path, "--underlay", str(tmp_path / "underlay" / "src")).stdout.split() == [str(dropin)]
    (underlay / "package.xml").write_text(versioned("1.16.0") % JSP_GUI)
    assert apply(tmp_path, "--underlay", str(tmp_path / "underlay" / "src")).stdout.split() == []


@pytest.mark.parametrize("platform", ["debian", "ubuntu"])
def test_install_deps_brings_what_urdf_tutorials_display_launch_starts(platform):
    """urdf_tutorial's display.launch starts joint_state_publisher(_gui), robot_state_publisher and rviz."""
    packages = resolved_packages(platform)
    if platform == "debian":
        expected = ["joint-state-publisher", "ros-robot-state-publisher", "rviz"]
        assert "joint-state-publisher-gui" not in packages  # Debian's 1.15.1 crashes: the drop-in is used
    else:
        expected = ["ros-noetic-joint-state-publisher", "ros-noetic-robot-state-publisher", "ros-noetic-rviz"]
    assert set(expected) <= set(packages), sorted(set(expected) - set(packages))
