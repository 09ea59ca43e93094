"""md5sums of a message package's sources (.msg, .srv, .action) through genmsg, without a build.

ROS 1 peers refuse a connection when the md5sums of the two sides differ, so the tests of the drop-in message
packages compare these values with the ones computed from the upstream package's own files. Actions are expanded
into their seven messages by actionlib_msgs' genaction.py, as catkin does in add_action_files.
"""
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Dict, Iterable, List

GENACTION_PATHS = ("/usr/lib/actionlib_msgs/genaction.py", "/opt/ros/noetic/lib/actionlib_msgs/genaction.py")


def installed_msg_dir(package: str) -> str:
    """The msg folder of an installed message package (rospkg when a ROS environment is set, else the usual
    prefixes: Debian's /usr/share, the ROS apt repository's /opt/ros/noetic/share)."""
    candidates = []
    try:
        import rospkg

        candidates.append(Path(rospkg.RosPack().get_path(package)))
    except Exception:  # rospkg missing, or the package is not on ROS_PACKAGE_PATH
        pass
    prefixes = [p for p in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep) if p]
    candidates += [Path(p) / "share" / package for p in prefixes + ["/opt/ros/noetic", "/usr"]]
    for candidate in candidates:
        if (candidate / "msg").is_dir():
            return str(candidate / "msg")
    raise FileNotFoundError("cannot find the .msg files of %s (install its -dev package)" % package)


def expand_actions(action_dir: Path, output_dir: str) -> None:
    genaction = next(path for path in GENACTION_PATHS if os.path.isfile(path))
    for action in sorted(action_dir.glob("*.action")):
        subprocess.run(
            [sys.executable, genaction, str(action), "-o", output_dir], check=True, stdout=subprocess.DEVNULL
        )


def source_md5sums(package_root: Path, package: str, dependencies: Iterable[str]) -> Dict[str, str]:
    """{"msg/Name" or "srv/Name": md5sum} of every type the package's sources define (actions' seven messages
    included)."""
    import genmsg
    from genmsg import msg_loader

    with tempfile.TemporaryDirectory() as generated:
        if (package_root / "action").is_dir():
            expand_actions(package_root / "action", generated)
        msg_dirs: List[str] = [str(package_root / "msg"), generated]
        search_path = {package: msg_dirs}
        search_path.update((dep, [installed_msg_dir(dep)]) for dep in dependencies)
        found = {}
        for folder in msg_dirs + [str(package_root / "srv")]:
            for path in sorted(Path(folder).glob("*.*")) if os.path.isdir(folder) else []:
                context = genmsg.MsgContext.create_default()
                full_name = "%s/%s" % (package, path.stem)
                if path.suffix == ".msg":
                    spec = msg_loader.load_msg_by_type(context, full_name, search_path)
                else:
                    spec = msg_loader.load_srv_from_file(context, str(path), full_name)
                msg_loader.load_depends(context, spec, search_path)
                found["%s/%s" % (path.suffix[1:], path.stem)] = genmsg.compute_md5(context, spec)
        return found
