"""rqt_plot and rqt_console are drop-ins (scripts/lib/dropins.py): used where the system has none, ignored where
ros-noetic-rqt-plot / ros-noetic-rqt-console are installed, and resolved to those on Ubuntu."""
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

TOOLS = ("rqt_plot", "rqt_console")


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
