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


def source_md5sums(
    package_root: Path, package: str, dependencies: Iterable[str], siblings: Iterable[str] = ()
) -> Dict[str, str]:
    """{"msg/Name" or "srv/Name": md5sum} of every type the package's sources define (actions' seven messages
    included); ``dependencies`` are installed message packages, ``siblings`` drop-in ones beside this package."""
    import genmsg
    from genmsg import msg_loader

    with tempfile.TemporaryDirectory() as generated:
        if (package_root / "action").is_dir():
            expand_actions(package_root / "action", generated)
        msg_dirs: List[str] = [str(package_root / "msg"), generated]
        search_path = {package: msg_dirs}
        search_path.update((dep, [installed_msg_dir(dep)]) for dep in dependencies)
        search_path.update((dep, [str(package_root.parent / dep / "msg")]) for dep in siblings)
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


def read_md5sums(path: Path) -> Dict[str, str]:
    """{"msg/Name": md5sum} from a text file of ``msg/Name md5sum`` lines (``#`` starts a comment)."""
    found = {}
    for line in path.read_text().splitlines():
        words = line.split("#", 1)[0].split()
        if words:
            type_key, md5sum = words
            found[type_key] = md5sum
    return found


def md5_tests(
    package_root: Path,
    package: str,
    dependencies: Iterable[str],
    upstream: Dict[str, str],
    siblings: Iterable[str] = (),
) -> dict:
    """The tests of a message package's md5sums against ``upstream`` ({"msg/Name": md5sum}), for a test module to
    take with ``globals().update(md5_tests(...))``: every upstream type and no other, each source md5sum, and each
    generated Python class's (skipped where no devel space with the package is sourced)."""
    import pytest

    @pytest.fixture(scope="module")
    def source() -> Dict[str, str]:
        pytest.importorskip("genmsg")
        return source_md5sums(package_root, package, dependencies, siblings)

    def test_every_upstream_type_and_no_other(source: Dict[str, str]) -> None:
        assert sorted(source) == sorted(upstream)

    @pytest.mark.parametrize("type_key", sorted(upstream))
    def test_source_md5sum_matches_upstream(source: Dict[str, str], type_key: str) -> None:
        assert source[type_key] == upstream[type_key]

    @pytest.mark.parametrize("type_key", sorted(upstream))
    def test_generated_python_md5sum_matches_upstream(type_key: str) -> None:
        kind, name = type_key.split("/")
        try:
            module = __import__("%s.%s" % (package, kind), fromlist=[name])
        except ImportError as error:
            pytest.skip("generated %s.%s not importable (source a devel space): %s" % (package, kind, error))
        assert getattr(module, name)._md5sum == upstream[type_key]

    return {
        "source": source,
        "test_every_upstream_type_and_no_other": test_every_upstream_type_and_no_other,
        "test_source_md5sum_matches_upstream": test_source_md5sum_matches_upstream,
        "test_generated_python_md5sum_matches_upstream": test_generated_python_md5sum_matches_upstream,
    }
