"""The rqt packages (rqt_gui, rqt_graph, rqt_logger_level, rqt_plot, rqt_console) are drop-ins
(scripts/lib/dropins.py): used where the system has none, ignored where ros-noetic-rqt-* are installed, and resolved
to those on Ubuntu."""
import os
import shutil
import subprocess
import sys

import pytest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SRC = os.path.join(REPO, "catkin_ws", "src")
sys.path.insert(0, os.path.join(REPO, "scripts", "lib"))
from dropins import find_dropins  # noqa: E402
from resolve_deps import load_table  # noqa: E402

TOOLS = ("rqt_gui", "rqt_graph", "rqt_logger_level", "rqt_plot", "rqt_console")


@pytest.mark.parametrize("tool", TOOLS)
def test_tool_is_a_dropin_with_a_row_naming_the_real_package_on_ubuntu(tool):
    assert find_dropins(SRC)[tool] == os.path.join(SRC, tool)
    assert load_table(os.path.join(REPO, "scripts", "lib", "rosdeps.tsv"))[tool]["ubuntu"] == [
        "ros-noetic-" + tool.replace("_", "-")
    ]


@pytest.mark.parametrize("tool", TOOLS)
def test_system_tool_makes_the_dropin_stand_aside(tmp_path, tool):
    src = tmp_path / "src"
    shutil.copytree(os.path.join(SRC, tool), str(src / tool), ignore=shutil.ignore_patterns("CATKIN_IGNORE"))
    system = tmp_path / "system" / "share" / tool
    system.mkdir(parents=True)
    (system / "package.xml").write_text(
        '<package format="3"><name>%s</name><version>0.4.0</version><description>d</description>'
        '<maintainer email="m@example.com">m</maintainer><license>BSD</license></package>' % tool
    )
    dropins = os.path.join(REPO, "scripts", "lib", "dropins.py")
    args = [sys.executable, dropins, "apply", "--src", str(src), "--prefix", str(tmp_path / "system")]
    result = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    assert result.returncode == 0 and result.stdout == ""
    assert (src / tool / "CATKIN_IGNORE").is_file()


@pytest.mark.parametrize("platform", ["debian", "ubuntu"])
def test_the_tutorials_bring_the_real_rqt_where_the_platform_has_it(platform):
    """beginner_tutorials depends on the five: Ubuntu installs the real ones, Debian what the drop-ins need."""
    resolver = os.path.join(REPO, "scripts", "lib", "resolve_deps.py")
    packages = subprocess.run(
        [sys.executable, resolver, "--platform", platform], stdout=subprocess.PIPE, universal_newlines=True
    ).stdout.split()
    real = {"ros-noetic-" + tool.replace("_", "-") for tool in TOOLS}
    if platform == "ubuntu":
        assert real <= set(packages)
    else:
        assert not real & set(packages)
        assert {"python3-python-qt-binding", "graphviz", "python3-pydot"} <= set(packages)
