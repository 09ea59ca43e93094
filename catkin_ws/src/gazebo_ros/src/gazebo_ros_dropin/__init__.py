"""ROS-free helpers of the gazebo_ros drop-in: whether a GUI can open, and which Gazebo args have no effect here."""
from __future__ import annotations

import os
import re
from typing import List, Mapping, Optional

LOCAL_DISPLAY = re.compile(r"^(?:unix)?:(\d+)(?:\.\d+)?$")
X11_SOCKET_DIR = "/tmp/.X11-unix"


def display_problem(environ: Mapping[str, str], socket_dir: str = X11_SOCKET_DIR) -> Optional[str]:
    """Why no window can open (a reason to log), or None when DISPLAY names a display that seems to be there.

    A local display (`:0`, `unix:1.0`) needs its X server's socket; a remote one (`host:10.0`, as ssh -X sets)
    is taken as given.
    """
    display = environ.get("DISPLAY", "").strip()
    if not display:
        return "DISPLAY is not set"
    local = LOCAL_DISPLAY.match(display)
    if local and not os.path.exists(os.path.join(socket_dir, "X" + local.group(1))):
        return "DISPLAY=%s has no X server (no %s)" % (display, os.path.join(socket_dir, "X" + local.group(1)))
    return None


def unsupported_arg_notes(recording: bool, physics: str, extra_gazebo_args: str) -> List[str]:
    """One warning per empty_world.launch arg set to something this simulator cannot do."""
    notes = []
    if recording:
        notes.append("recording:=true: this simulator writes no Gazebo state log (record topics with rosbag)")
    if physics.strip() != "ode":
        notes.append("physics:=%s: the engine is always ODE here" % physics.strip())
    if extra_gazebo_args.strip():
        notes.append(
            "extra_gazebo_args [%s] ignored: this launch file starts the simulator without a gzserver command line "
            "(rosrun gazebo_ros gzserver takes Gazebo's options)" % extra_gazebo_args.strip()
        )
    return notes


def parse_bool(text: str) -> bool:
    """roslaunch's spelling of a boolean arg ("true", "1", ...)."""
    value = text.strip().lower()
    if value in ("true", "1", "yes", "on"):
        return True
    if value in ("false", "0", "no", "off", ""):
        return False
    raise ValueError("not a boolean: %r" % text)
