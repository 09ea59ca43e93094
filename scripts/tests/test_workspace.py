"""Workspace-wide checks: lint, the catkin-tools build, formatting, and the dependency list."""
import os
import re
import shutil
import subprocess
import sys

import pytest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SRC = os.path.join(REPO, "catkin_ws", "src")
PACKAGES = sorted(d for d in os.listdir(SRC) if os.path.isfile(os.path.join(SRC, d, "package.xml")))


def run(command, **kwargs):
    return subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, **kwargs)


def tracked_files(*suffixes):
    listing = run(["git", "ls-files", "--cached", "--others", "--exclude-standard"], cwd=REPO).stdout.split()
    return [os.path.join(REPO, f) for f in listing if f.endswith(suffixes) and os.path.exists(os.path.join(REPO, f))]


@pytest.mark.parametrize("package", PACKAGES)
def test_catkin_lint_clean(package):
    result = run(["catkin_lint", "-W2", "--strict", "--package-path", SRC, os.path.join(SRC, package)])
    assert result.returncode == 0, result.stdout


def test_builds_with_catkin_tools():
    """Many users build with `catkin build`: the same sources in a workspace of its own (kept for speed)."""
    workspace = os.path.join(REPO, ".catkin_tools_ws")
    os.makedirs(workspace, exist_ok=True)
    if not os.path.islink(os.path.join(workspace, "src")):
        os.symlink(SRC, os.path.join(workspace, "src"))
    result = run(
        [
            "catkin",
            "build",
            "--workspace",
            workspace,
            "--no-status",
            "--no-notify",
            "--summarize",
            "--cmake-args",
            "-DCMAKE_BUILD_TYPE=Release",
            "-DPYTHON_EXECUTABLE=/usr/bin/python3",
        ]
    )
    assert result.returncode == 0, result.stdout[-5000:]


def test_cpp_formatted():
    files = tracked_files(".cpp", ".c", ".h")
    assert files
    result = run(["clang-format", "--dry-run", "--Werror", "--style=file"] + files, cwd=REPO)
    assert result.returncode == 0, result.stdout[-5000:]


def test_python_formatted():
    """black with the repository's pyproject.toml; older blacks (Ubuntu 20.04 has 19.10) format differently."""
    version = run(["black", "--version"]).stdout if shutil.which("black") else ""
    match = re.search(r"(\d+)\.\d+", version)
    if not match or int(match.group(1)) < 23:
        pytest.skip("needs black >= 23 (found: %s)" % (version.strip() or "none"))
    # Python files, and the extension-less executables in nodes/
    files = tracked_files(".py") + [
        f
        for f in tracked_files("")
        if os.path.basename(os.path.dirname(f)) == "nodes" and "." not in os.path.basename(f)
    ]
    result = run(["black", "--check", "--quiet"] + files, cwd=REPO)
    assert result.returncode == 0, result.stdout[-5000:]


def test_shell_scripts_parse():
    for script in tracked_files(".sh") + [os.path.join(REPO, ".ci", "run")]:
        result = run(["bash", "-n", script])
        assert result.returncode == 0, script + ": " + result.stdout


def test_launch_files_keep_nodes_on_loopback():
    """ROS 1 has no authentication: every launch file gives its nodes ROS_IP=127.0.0.1 unless the user set one."""
    loopback = '<env name="ROS_IP" value="$(optenv ROS_IP 127.0.0.1)"/>'
    launch_files = [f for f in tracked_files(".launch") if "/launch/" in f]
    assert launch_files
    assert [f for f in launch_files if loopback not in open(f).read()] == []


@pytest.mark.parametrize("platform", ["debian", "ubuntu"])
def test_every_dependency_resolves(platform):
    """Each key the package.xml files name has a system package on both supported platforms."""
    result = run([sys.executable, os.path.join(REPO, "scripts", "lib", "resolve_deps.py"), "--platform", platform])
    assert result.returncode == 0, result.stdout
    packages = result.stdout.split()
    assert "catkin-lint" in packages or "python3-catkin-lint" in packages
    if platform == "ubuntu":
        assert "ros-noetic-roscpp" in packages and "libroscpp-dev" not in packages
    else:
        assert "libroscpp-dev" in packages


def test_debian_dependencies_are_installable():
    """Every Debian package name the resolver gives exists in the archive (a typo would break a fresh machine)."""
    if not shutil.which("apt-cache") or "debian" not in open("/etc/os-release").read():
        pytest.skip("only checkable on Debian")
    packages = run(
        [sys.executable, os.path.join(REPO, "scripts", "lib", "resolve_deps.py"), "--platform", "debian"]
    ).stdout.split()
    unknown = [
        p
        for p in packages
        if "Candidate: (none)" in run(["apt-cache", "policy", p]).stdout
        or not run(["apt-cache", "policy", p]).stdout.strip()
    ]
    assert not unknown, unknown
