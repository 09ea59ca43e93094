#!/usr/bin/env python3
"""Workspace drop-ins: packages that stand in for a system ROS package on systems that lack it.

A drop-in is a workspace package whose package.xml exports <dropin/> (catkin_ws/src/xacro, gazebo_ros,
controller_manager, control_msgs, controller_manager_msgs, kobuki_msgs, turtlebot_gazebo, ...). It stands aside
(gets a CATKIN_IGNORE file, which catkin_make, catkin-tools, rospack and rospkg all honour) wherever a real package
of the same name exists:
  - installed: <prefix>/share/<name>/package.xml for the prefixes /opt/ros/noetic, /usr and those on
    CMAKE_PREFIX_PATH outside the workspace;
  - in the user's own workspace: another package folder of that name under the workspace's src;
  - in an underlay workspace: a package folder below a ROS_PACKAGE_PATH entry outside the workspace, or below the
    source space a devel-space prefix on CMAKE_PREFIX_PATH names in its .catkin file.
A copy of a drop-in (installed, or in another workspace) is never the real package. Neither is an installed or
underlay package older than the version its drop-in names as the first working one (<dropin fixed_in="1.15.2"/>:
Debian's joint_state_publisher_gui 1.15.1 crashes): the drop-in is used ahead of it, as the workspace comes first
on ROS_PACKAGE_PATH, CMAKE_PREFIX_PATH and PYTHONPATH. Where no real package exists, a CATKIN_IGNORE written here
is removed again (one a person wrote is left alone).

  dropins.py apply [--src DIR] [--devel DIR] [--prefix P ...] [--underlay DIR ...]
      write or remove the CATKIN_IGNORE files (and, for an ignored drop-in, its leftovers in the devel space);
      print the folders of the drop-ins in use, one a line; say what was decided on stderr
  dropins.py pypi-missing --target DIR [--src DIR] [--prefix P ...] [--underlay DIR ...]
      print the pypi-requirements.txt files of the drop-ins in use that DIR does not satisfy yet

Standard library only: scripts/install_deps.sh runs this before anything is installed.
"""
import argparse
import os
import re
import shutil
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_SRC = os.path.normpath(os.path.join(HERE, "..", "..", "catkin_ws", "src"))
MARKER = "# written by scripts/lib/dropins.py"
REQUIREMENT = re.compile(r"^\s*([A-Za-z0-9_.-]+)==([A-Za-z0-9_.+-]+)")


def package_folders(top, max_depth=None):
    """[(name, folder, is a drop-in, ignored by a person)] of the packages below top, as catkin and rospack find
    them: nothing below a package folder, no hidden folders, nothing below a CATKIN_IGNORE a person wrote (a package
    folder holding one is still listed, flagged). max_depth limits how far below top an underlay is searched."""
    found = []
    top_depth = top.rstrip(os.sep).count(os.sep)
    for root, dirs, files in os.walk(top):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        if max_depth is not None and root.count(os.sep) - top_depth >= max_depth:
            dirs[:] = []
        ignored = "CATKIN_IGNORE" in files and not written_here(os.path.join(root, "CATKIN_IGNORE"))
        if ignored:
            dirs[:] = []
        if "package.xml" not in files:
            continue
        dirs[:] = []
        manifest = os.path.join(root, "package.xml")
        try:
            name = ET.parse(manifest).findtext("name").strip()
        except (ET.ParseError, AttributeError):
            continue  # not our business: catkin names the broken manifest itself
        found.append((name, root, is_dropin(manifest), ignored))
    return found


def written_here(ignore):
    with open(ignore) as ignore_file:
        return ignore_file.read().startswith(MARKER)


def find_dropins(src_dir):
    """{package name: folder} of the drop-ins below src_dir (a package folder's subfolders are not searched)."""
    return {name: folder for name, folder, dropin, _ in package_folders(src_dir) if dropin}


def workspace_packages(src_dir):
    """{package name: folder} of the packages below src_dir that are not drop-ins (the user's own)."""
    return {name: folder for name, folder, dropin, ignored in package_folders(src_dir) if not (dropin or ignored)}


def underlay_sources(workspace):
    """Folders holding an underlay workspace's packages: ROS_PACKAGE_PATH entries and the source spaces that
    devel-space prefixes on CMAKE_PREFIX_PATH list in their .catkin file, all outside the workspace and outside
    the system's share folders (those are searched by system_package)."""
    sources = [p for p in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        marker = os.path.join(prefix, ".catkin") if prefix else ""
        if marker and os.path.isfile(marker):
            with open(marker) as catkin_file:
                sources.extend(p for p in catkin_file.read().strip().split(";") if p)
    system_shares = {os.path.realpath(os.path.join(p, "share")) for p in ("/opt/ros/noetic", "/usr")}
    kept = []
    for source in sources:
        real = os.path.realpath(source)
        if os.path.isdir(real) and real not in system_shares and not inside(real, workspace) and real not in kept:
            kept.append(real)
    return kept


def inside(path, folder):
    folder = os.path.realpath(folder)
    return path == folder or path.startswith(folder + os.sep)


def system_prefixes(workspace):
    """/opt/ros/noetic, /usr and CMAKE_PREFIX_PATH's entries, without those inside the workspace."""
    prefixes = ["/opt/ros/noetic", "/usr"] + os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep)
    kept = []
    for prefix in prefixes:
        if prefix and not inside(os.path.realpath(prefix), workspace) and prefix not in kept:
            kept.append(prefix)
    return kept


def dropin_element(manifest):
    export = ET.parse(manifest).find("export")
    return export.find("dropin") if export is not None else None


def is_dropin(manifest):
    return dropin_element(manifest) is not None


def version_tuple(text):
    """(1, 15, 2) for "1.15.2"; the parts that are not numbers count as 0."""
    return tuple(int(part) if part.isdigit() else 0 for part in text.strip().split("."))


def broken_version(manifest, fixed_in):
    """The version of the package at manifest when it is older than fixed_in (its drop-in's first working one)."""
    if not fixed_in:
        return None
    version = (ET.parse(manifest).findtext("version") or "0").strip()
    return version if version_tuple(version) < version_tuple(fixed_in) else None


def system_package(name, prefixes):
    """The package.xml of a package `name` installed under one of the prefixes, or None.

    An installed copy of a drop-in (an install space of this or another workspace) is not the system's package.
    """
    for prefix in prefixes:
        manifest = os.path.join(prefix, "share", name, "package.xml")
        if os.path.isfile(manifest) and not is_dropin(manifest):
            return manifest
    return None


# How deep below a ROS_PACKAGE_PATH entry an underlay's packages are looked for (src/<repository>/<package> is 2).
UNDERLAY_DEPTH = 4


def underlay_packages(sources):
    """{package name: folder} of the real (not drop-in) packages in the underlays' source folders, first one wins."""
    found = {}
    for source in sources:
        for name, folder, dropin, ignored in package_folders(source, UNDERLAY_DEPTH):
            if not (dropin or ignored):
                found.setdefault(name, folder)
    return found


def decide(src_dir, prefixes, underlays=()):
    """[(name, folder, the real package's folder or None, [(broken package's folder, its version)])] for every
    drop-in: the user's own package of that name in src_dir first, then an installed one, then one in an underlay;
    installed and underlay ones older than the drop-in's fixed_in do not count (the drop-in is used ahead of them)."""
    own = workspace_packages(src_dir)
    elsewhere = underlay_packages(underlays)
    decisions = []
    for name, folder in sorted(find_dropins(src_dir).items()):
        fixed_in = dropin_element(os.path.join(folder, "package.xml")).get("fixed_in")
        manifest = system_package(name, prefixes)
        real, broken = own.get(name), []
        for candidate in (os.path.dirname(manifest) if manifest else None, elsewhere.get(name)):
            if real or not candidate:
                continue
            version = broken_version(os.path.join(candidate, "package.xml"), fixed_in)
            if version:
                broken.append((candidate, version))
            else:
                real = candidate
        decisions.append((name, folder, real, broken))
    return decisions


def apply(src_dir, prefixes, devel_dir=None, log=sys.stderr, underlays=()):
    """Write/remove the CATKIN_IGNORE files; return the folders of the drop-ins in use."""
    in_use = []
    for name, folder, real, broken in decide(src_dir, prefixes, underlays):
        ignore = os.path.join(folder, "CATKIN_IGNORE")
        if real:
            if not os.path.exists(ignore):
                with open(ignore, "w") as ignore_file:
                    ignore_file.write("%s: the real package is %s\n" % (MARKER, real))
            for leftover in (("share", name), ("lib", name)) if devel_dir else ():
                if os.path.isdir(os.path.join(devel_dir, *leftover)):
                    shutil.rmtree(os.path.join(devel_dir, *leftover))
            log.write("dropins: %s: the real %s is used (%s ignored)\n" % (name, real, folder))
            continue
        if os.path.exists(ignore) and written_here(ignore):
            os.remove(ignore)
        if os.path.exists(ignore):
            log.write("dropins: %s: %s has a CATKIN_IGNORE of its own: left alone\n" % (name, folder))
            continue
        for shadowed, version in broken:
            log.write(
                "dropins: %s: %s is version %s, which does not work: the workspace's drop-in is found ahead of it\n"
                % (name, shadowed, version)
            )
        if not broken:
            log.write("dropins: %s: no real package found, the workspace's drop-in is used\n" % name)
        in_use.append(folder)
    return in_use


def unsatisfied_requirements(requirements_file, target):
    """The `name==version` pins of a requirements file that have no <name>-<version>.dist-info in target."""
    missing = []
    with open(requirements_file) as pins:
        for line in pins:
            match = REQUIREMENT.match(line)
            if match:
                name, version = match.group(1).replace("-", "_"), match.group(2)
                if not os.path.isdir(os.path.join(target, "%s-%s.dist-info" % (name, version))):
                    missing.append("%s==%s" % match.groups())
    return missing


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("command", choices=("apply", "pypi-missing"))
    parser.add_argument("--src", default=DEFAULT_SRC, help="the workspace's src folder")
    parser.add_argument("--devel", help="the devel space, to remove an ignored drop-in's leftovers from")
    parser.add_argument("--prefix", action="append", help="a system prefix (repeatable; default: see above)")
    parser.add_argument(
        "--underlay", action="append", help="an underlay's source folder (repeatable; default: see above)"
    )
    parser.add_argument("--target", help="pypi-missing: the folder the PyPI libraries are installed into")
    args = parser.parse_args(argv)
    workspace = os.path.dirname(os.path.abspath(args.src))
    prefixes = args.prefix or system_prefixes(workspace)
    underlays = args.underlay or underlay_sources(workspace)
    if args.command == "apply":
        for folder in apply(args.src, prefixes, args.devel, underlays=underlays):
            print(folder)
        return 0
    if not args.target:
        parser.error("pypi-missing needs --target")
    for name, folder, real, _ in decide(args.src, prefixes, underlays):
        requirements = os.path.join(folder, "pypi-requirements.txt")
        if not real and os.path.isfile(requirements) and unsatisfied_requirements(requirements, args.target):
            print(requirements)
    return 0


if __name__ == "__main__":
    sys.exit(main())
