"""Upstream's own tests run unchanged against this workspace. A package's test files (its ``test/`` and ``scripts/``
folders) are read at test time from where the tester keeps the upstream repository (a checkout or a git mirror,
else a mirror cloned into ROS_HOME when the network allows), written into a scratch catkin package of the same
name, built in a scratch workspace over ours, and run with rostest. Nothing of upstream's is kept in the project.

The scratch package's CMakeLists registers only what the caller names: the gtest rostests with their source, or a
plain rostest whose test nodes are upstream's scripts."""
from __future__ import annotations

import os
import subprocess
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

GIT_TIMEOUT = 300.0  # s: a clone of gazebo_ros_pkgs' history over a slow link


@dataclass(frozen=True)
class UpstreamFile:
    data: bytes
    executable: bool


class UpstreamSource:
    """The files of one revision of an upstream repository: ``location`` is a work tree (files read as they are)
    or a git directory (a bare mirror; files read at ``ref``)."""

    def __init__(self, location: str, ref: str = "HEAD") -> None:
        self.location = location
        self.ref = ref
        self._git_dir = _git_dir(location)
        if self._git_dir is None and not os.path.isdir(location):
            raise FileNotFoundError(f"upstream repository '{location}': no such directory")

    def files_under(self, folder: str) -> Dict[str, UpstreamFile]:
        """Every file below ``folder`` (a path in the repository), by its path in the repository."""
        folder = folder.strip("/")
        if self._git_dir is None:
            found = {}
            root = os.path.join(self.location, folder)
            for directory, _, names in os.walk(root):
                for name in names:
                    path = os.path.join(directory, name)
                    with open(path, "rb") as file:
                        relative = os.path.relpath(path, self.location)
                        found[relative] = UpstreamFile(file.read(), os.access(path, os.X_OK))
            return found
        listing = self._git("ls-tree", "-r", "-z", self.ref, "--", folder + "/").decode()
        found = {}
        for entry in filter(None, listing.split("\0")):
            meta, path = entry.split("\t", 1)
            mode, kind, blob = meta.split()
            if kind == "blob":
                found[path] = UpstreamFile(self._git("cat-file", "blob", blob), mode == "100755")
        return found

    def _git(self, *args: str) -> bytes:
        return subprocess.run(
            ["git", "--git-dir", self._git_dir, *args], check=True, capture_output=True, timeout=GIT_TIMEOUT
        ).stdout


def _git_dir(location: str) -> Optional[str]:
    """The git directory of ``location`` if it is one (bare) or holds one (.git), else None."""
    if os.path.isfile(os.path.join(location, "HEAD")) and os.path.isdir(os.path.join(location, "objects")):
        return location
    inner = os.path.join(location, ".git")
    return inner if os.path.isdir(inner) else None


def find_upstream(env_var: str, url: str, cache: str, ref: str) -> Tuple[Optional[UpstreamSource], str]:
    """The upstream repository: where ``env_var`` points, else a mirror in ``cache`` (cloned from ``url`` now if
    missing). (None, why and how to provide it) where neither is there: the same text for every test of ``url``."""
    location = os.environ.get(env_var, "")
    if location:
        return UpstreamSource(location, ref), f"${env_var} ({location})"
    if not os.path.isdir(cache):
        try:
            subprocess.run(
                ["git", "clone", "--quiet", "--mirror", url, cache],
                check=True,
                capture_output=True,
                timeout=GIT_TIMEOUT,
            )
        except (subprocess.SubprocessError, OSError) as error:
            return None, (
                f"no upstream source of {url}: ${env_var} is not set and it cannot be cloned into {cache}"
                f" ({_failure(error)}); set {env_var} to a checkout or git mirror of it"
                f" (git clone --mirror {url} DIR) or put that mirror at {cache}"
            )
    if not _has_commit(cache, ref):  # a clone still running or left half made (by a run stopped mid-clone)
        return None, (
            f"no upstream source of {url}: ${env_var} is not set and {cache} has no commit {ref} (a clone in"
            f" progress or a broken one); remove it, or set {env_var} to a checkout or git mirror of it"
        )
    return UpstreamSource(cache, ref), f"mirror {cache}"


def _has_commit(location: str, ref: str) -> bool:
    """Whether the git repository at ``location`` resolves ``ref`` to a commit."""
    try:
        subprocess.run(
            ["git", "--git-dir", location, "rev-parse", "--verify", "--quiet", ref + "^{commit}"],
            check=True,
            capture_output=True,
            timeout=GIT_TIMEOUT,
        )
    except (subprocess.SubprocessError, OSError):
        return False
    return True


def _failure(error: Exception) -> str:
    """Why git failed, in one line: its last line of stderr, or the error."""
    if isinstance(error, subprocess.TimeoutExpired):
        return f"no answer in {error.timeout:g} s"
    stderr = getattr(error, "stderr", None) or b""
    lines = stderr.decode(errors="replace").strip().splitlines()
    return lines[-1] if lines else str(error)


@dataclass(frozen=True)
class GTest:
    """A gtest rostest of the scratch package: CMake target, the .test file and the test's sources (package paths),
    and what else it links (CMake variables, e.g. ``${OpenCV_LIBRARIES}``)."""

    target: str
    test_file: str
    sources: Tuple[str, ...]
    libraries: Tuple[str, ...] = ()


@dataclass(frozen=True)
class ScratchPackage:
    """A catkin package named ``name`` holding upstream's files. ``components``: catkin packages its tests build
    with; ``opencv``: OpenCV modules they link (none: OpenCV is not looked for)."""

    name: str
    components: Tuple[str, ...] = ("roscpp",)
    opencv: Tuple[str, ...] = ()
    gtests: Tuple[GTest, ...] = ()

    def package_xml(self) -> str:
        depends = "".join(f"  <depend>{component}</depend>\n" for component in self.components)
        return (
            '<?xml version="1.0"?>\n<package format="3">\n'
            f"  <name>{self.name}</name>\n  <version>0.0.0</version>\n"
            "  <description>scratch package: upstream's tests, built at test time</description>\n"
            '  <maintainer email="dev@example.com">test</maintainer>\n  <license>BSD</license>\n'
            "  <buildtool_depend>catkin</buildtool_depend>\n"
            f"{depends}  <test_depend>rostest</test_depend>\n</package>\n"
        )

    def cmakelists(self) -> str:
        lines = [
            "cmake_minimum_required(VERSION 3.0.2)",
            f"project({self.name})",
            f"find_package(catkin REQUIRED COMPONENTS {' '.join(self.components)})",
        ]
        if self.opencv:
            lines.append(f"find_package(OpenCV REQUIRED COMPONENTS {' '.join(self.opencv)})")
        lines += ["catkin_package()", "include_directories(${catkin_INCLUDE_DIRS} ${OpenCV_INCLUDE_DIRS})"]
        if self.gtests:
            # Boost's bind placeholders (_1) in the global namespace, as Ubuntu 20.04's Boost 1.71 puts them, for
            # the tests written against it (Debian 12's Boost 1.74 keeps them in boost::placeholders).
            lines.append("add_definitions(-DBOOST_BIND_GLOBAL_PLACEHOLDERS)")
            lines.append("add_compile_options(-include boost/bind.hpp)")
        lines.append("find_package(rostest REQUIRED)")
        for test in self.gtests:
            lines.append(f"add_rostest_gtest({test.target} {test.test_file} {' '.join(test.sources)})")
            lines.append(f"target_link_libraries({test.target} ${{catkin_LIBRARIES}} {' '.join(test.libraries)})")
        return "\n".join(lines) + "\n"

    def write(self, folder: str, files: Dict[str, UpstreamFile], strip: str) -> None:
        """Write the package into ``folder``: upstream's ``files`` at their paths less the prefix ``strip``, and
        the package's own package.xml and CMakeLists.txt."""
        for path, upstream in files.items():
            target = os.path.join(folder, os.path.relpath(path, strip))
            os.makedirs(os.path.dirname(target), exist_ok=True)
            with open(target, "wb") as file:
                file.write(upstream.data)
            os.chmod(target, 0o755 if upstream.executable else 0o644)
        with open(os.path.join(folder, "package.xml"), "w") as file:
            file.write(self.package_xml())
        with open(os.path.join(folder, "CMakeLists.txt"), "w") as file:
            file.write(self.cmakelists())


@dataclass
class Results:
    """What rostest's JUnit files say: test cases run (a skipped one not), the names of the failed or erroring ones
    with their text, and the names of the skipped ones with their reason."""

    tests: int = 0
    failed: List[str] = field(default_factory=list)
    skipped: List[str] = field(default_factory=list)


def read_results(folder: str) -> Results:
    """The test cases of every JUnit XML file below ``folder`` (rostest's results and its test nodes')."""
    results = Results()
    for directory, _, names in os.walk(folder):
        for name in sorted(names):
            if not name.endswith(".xml"):
                continue
            root = ElementTree.parse(os.path.join(directory, name)).getroot()
            for case in root.iter("testcase"):
                label = f"{name}: {case.get('classname')}.{case.get('name')}"
                skip = case.find("skipped")
                if skip is not None or case.get("result") == "skipped":
                    reason = skip.get("message") if skip is not None else ""
                    results.skipped.append(f"{label}: {reason or 'skipped'}")
                    continue
                results.tests += 1
                for problem in list(case.findall("failure")) + list(case.findall("error")):
                    text = (problem.get("message") or "") + (problem.text or "")
                    results.failed.append(f"{label}: {text.strip()}")
    return results


def shell_command(setup: str, command: Sequence[str]) -> List[str]:
    """``command`` run by bash after sourcing the catkin ``setup`` file."""
    quoted = " ".join("'" + part.replace("'", "'\\''") + "'" for part in command)
    return ["bash", "-c", f". '{setup}' && exec {quoted}"]
