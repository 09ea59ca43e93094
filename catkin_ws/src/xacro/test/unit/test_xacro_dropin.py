"""The xacro drop-in's glue: PyPI's xacro with $(find) through the ROS package path (no ROS master needed)."""
from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import types
from pathlib import Path

import pytest
import rospkg

PACKAGE_ROOT = Path(__file__).resolve().parents[2]
if (PACKAGE_ROOT / "CATKIN_IGNORE").exists():  # scripts/lib/dropins.py: the system's xacro is used here
    pytest.skip(
        "the drop-in is ignored: " + (PACKAGE_ROOT / "CATKIN_IGNORE").read_text().strip(), allow_module_level=True
    )
sys.path.insert(0, str(PACKAGE_ROOT / "src"))

import xacro_dropin  # noqa: E402


def make_package(root: Path, name: str) -> Path:
    folder = root / name
    (folder / "urdf").mkdir(parents=True)
    (folder / "package.xml").write_text(
        '<package format="3"><name>%s</name><version>0.0.1</version><description>d</description>'
        '<maintainer email="dev@example.com">m</maintainer><license>BSD</license></package>' % name
    )
    return folder


@pytest.fixture
def package_path(tmp_path: Path) -> Path:
    parts = make_package(tmp_path, "dropin_test_parts")
    (parts / "urdf" / "leg.xacro").write_text(
        textwrap.dedent(
            """\
            <robot xmlns:xacro="http://www.ros.org/wiki/xacro">
              <xacro:macro name="leg" params="n length">
                <link name="leg_${n}"><visual><geometry><box size="0.01 0.01 ${length}"/></geometry></visual></link>
              </xacro:macro>
            </robot>
            """
        )
    )
    return tmp_path


def test_finder_answers_as_rospack(package_path: Path) -> None:
    find = xacro_dropin.ros_package_finder(rospkg.RosPack(ros_paths=[str(package_path)]))
    assert find("dropin_test_parts") == str(package_path / "dropin_test_parts")


def test_finder_names_the_missing_package(package_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(package_path))
    find = xacro_dropin.ros_package_finder(rospkg.RosPack(ros_paths=[str(package_path)]))
    with pytest.raises(xacro_dropin.PackageNotFound) as raised:
        find("no_such_package")
    assert "$(find no_such_package): package 'no_such_package' not found on the ROS package path" in str(raised.value)
    assert str(package_path) in str(raised.value)


def test_hook_replaces_both_find_lookups() -> None:
    module = types.ModuleType("substitution_args")
    module._eval_find = lambda package: "/ament/" + package
    module._eval_dict = {"find": module._eval_find, "env": None}
    xacro_dropin.use_ros_package_path(module, lambda package: "/ros/" + package)
    assert module._eval_find("p") == "/ros/p"
    assert module._eval_dict["find"]("p") == "/ros/p"


def test_hook_refuses_a_library_without_it() -> None:
    with pytest.raises(RuntimeError, match="no _eval_find/_eval_dict hook"):
        xacro_dropin.use_ros_package_path(types.ModuleType("substitution_args"), str)


def test_the_pinned_pypi_library_has_the_hook() -> None:
    """scripts/install_deps.sh installed the pinned xacro; its resolver is where the drop-in expects it."""
    xacro = xacro_dropin.import_pypi_xacro()
    from xacro import substitution_args

    assert hasattr(substitution_args, "_eval_find") and "find" in substitution_args._eval_dict
    pin = (PACKAGE_ROOT / "pypi-requirements.txt").read_text()
    version = [line.split("==")[1].split()[0] for line in pin.splitlines() if line.startswith("xacro==")][0]
    assert os.path.isdir(os.path.join(os.path.dirname(os.path.dirname(xacro.__file__)), "xacro-%s.dist-info" % version))


def run_xacro(args: list, package_path: Path) -> subprocess.CompletedProcess:
    env = dict(os.environ, ROS_PACKAGE_PATH=str(package_path), PYTHONPATH=str(PACKAGE_ROOT / "src"))
    return subprocess.run(
        ["/usr/bin/python3", str(PACKAGE_ROOT / "xacro")] + args,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        universal_newlines=True,
        env=env,
    )


def test_command_expands_find_and_args(package_path: Path, tmp_path: Path) -> None:
    robot = tmp_path / "robot.urdf.xacro"
    robot.write_text(
        textwrap.dedent(
            """\
            <robot name="walker" xmlns:xacro="http://www.ros.org/wiki/xacro">
              <xacro:arg name="length" default="0.2"/>
              <xacro:include filename="$(find dropin_test_parts)/urdf/leg.xacro"/>
              <xacro:leg n="1" length="$(arg length)"/>
              <link name="marker"><visual><geometry>
                <mesh filename="$(find dropin_test_parts)/urdf/leg.xacro"/>
              </geometry></visual></link>
            </robot>
            """
        )
    )
    result = run_xacro([str(robot), "length:=0.35"], package_path)
    assert result.returncode == 0, result.stderr
    assert '<box size="0.01 0.01 0.35"/>' in result.stdout
    assert 'filename="%s/dropin_test_parts/urdf/leg.xacro"' % package_path in result.stdout


def test_command_accepts_inorder_with_noetics_note(package_path: Path, tmp_path: Path) -> None:
    robot = tmp_path / "plain.urdf.xacro"
    robot.write_text('<robot name="plain" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"/></robot>')
    result = run_xacro(["--inorder", str(robot)], package_path)
    assert result.returncode == 0, result.stderr
    assert "in-order processing became default in ROS Melodic" in result.stderr
    assert '<robot name="plain">' in result.stdout


def test_command_without_the_library_says_how_to_get_it(tmp_path: Path, package_path: Path) -> None:
    env = dict(
        os.environ,
        XACRO_PYPI_DIR=str(tmp_path / "empty"),
        PYTHONPATH=str(PACKAGE_ROOT / "src"),
        ROS_PACKAGE_PATH=str(package_path),
    )
    # -S: without site-packages, as on a machine where no xacro was ever installed
    result = subprocess.run(
        [
            "/usr/bin/python3",
            "-S",
            "-c",
            "import sys; sys.path.append('/usr/lib/python3/dist-packages');"
            "import xacro_dropin; sys.exit(xacro_dropin.main(['x.xacro']))",
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        universal_newlines=True,
        env=env,
    )
    assert result.returncode == 1
    assert "PyPI's xacro library is not installed" in result.stderr and "scripts/install_deps.sh" in result.stderr
