#!/usr/bin/env python3
"""Workspace drop-ins: packages that stand in for a system ROS package on systems that lack it.

A drop-in is a workspace package whose package.xml exports <dropin/> (catkin_ws/src/xacro, gazebo_ros, controller_manager
and the message packages control_msgs and controller_manager_msgs). Where a
package of the same name is installed outside the workspace (<prefix>/share/<name>/package.xml, for the prefixes
/opt/ros/noetic, /usr and those on CMAKE_PREFIX_PATH), the drop-in gets a CATKIN_IGNORE file: catkin_make,
catkin-tools, rospack and rospkg all skip a folder holding one, so the system's package is the one found and
nothing of the workspace shadows it. Where the system has no such package, a CATKIN_IGNORE written here is
removed again (one a person wrote is left alone).

  dropins.py apply [--src DIR] [--devel DIR] [--prefix P ...]
      write or remove the CATKIN_IGNORE files (and, for an ignored drop-in, its leftovers in the devel space);
      print the folders of the drop-ins in use, one a line; say what was decided on stderr
  dropins.py pypi-missing --target DIR [--src DIR] [--prefix P ...]
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


def find_dropins(src_dir):
    """{package name: folder} of the drop-ins below src_dir (a package folder's subfolders are not searched)."""
    dropins = {}
    for root, dirs, files in os.walk(src_dir):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        if "package.xml" not in files:
            continue
        dirs[:] = []  # as catkin: nothing below a package
        if is_dropin(os.path.join(root, "package.xml")):
            dropins[ET.parse(os.path.join(root, "package.xml")).findtext("name").strip()] = root
    return dropins


def system_prefixes(workspace):
    """/opt/ros/noetic, /usr and CMAKE_PREFIX_PATH's entries, without those inside the workspace."""
    workspace = os.path.realpath(workspace)
    prefixes = ["/opt/ros/noetic", "/usr"] + os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep)
    kept = []
    for prefix in prefixes:
        real = os.path.realpath(prefix) if prefix else ""
        if real and real != workspace and not real.startswith(workspace + os.sep) and prefix not in kept:
            kept.append(prefix)
    return kept


def is_dropin(manifest):
    export = ET.parse(manifest).find("export")
    return export is not None and export.find("dropin") is not None


def system_package(name, prefixes):
    """The package.xml of a package `name` installed under one of the prefixes, or None.

    An installed copy of a drop-in (an install space of this or another workspace) is not the system's package.
    """
    for prefix in prefixes:
        manifest = os.path.join(prefix, "share", name, "package.xml")
        if os.path.isfile(manifest) and not is_dropin(manifest):
            return manifest
    return None


def decide(src_dir, prefixes):
    """[(name, folder, system package.xml or None)] for every drop-in."""
    return [(name, folder, system_package(name, prefixes)) for name, folder in sorted(find_dropins(src_dir).items())]


def apply(src_dir, prefixes, devel_dir=None, log=sys.stderr):
    """Write/remove the CATKIN_IGNORE files; return the folders of the drop-ins in use."""
    in_use = []
    for name, folder, manifest in decide(src_dir, prefixes):
        ignore = os.path.join(folder, "CATKIN_IGNORE")
        if manifest:
            if not os.path.exists(ignore):
                with open(ignore, "w") as ignore_file:
                    ignore_file.write("%s: the system has %s\n" % (MARKER, os.path.dirname(manifest)))
            for leftover in (("share", name), ("lib", name)) if devel_dir else ():
                if os.path.isdir(os.path.join(devel_dir, *leftover)):
                    shutil.rmtree(os.path.join(devel_dir, *leftover))
            log.write("dropins: %s: the system's %s is used (%s ignored)\n" % (name, os.path.dirname(manifest), folder))
            continue
        if os.path.exists(ignore) and open(ignore).read().startswith(MARKER):
            os.remove(ignore)
        if os.path.exists(ignore):
            log.write("dropins: %s: %s has a CATKIN_IGNORE of its own: left alone\n" % (name, folder))
            continue
        log.write("dropins: %s: the system has none, the workspace's drop-in is used\n" % name)
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
    parser.add_argument("--target", help="pypi-missing: the folder the PyPI libraries are installed into")
    args = parser.parse_args(argv)
    prefixes = args.prefix or system_prefixes(os.path.dirname(os.path.abspath(args.src)))
    if args.command == "apply":
        for folder in apply(args.src, prefixes, args.devel):
            print(folder)
        return 0
    if not args.target:
        parser.error("pypi-missing needs --target")
    for name, folder, manifest in decide(args.src, prefixes):
        requirements = os.path.join(folder, "pypi-requirements.txt")
        if not manifest and os.path.isfile(requirements) and unsatisfied_requirements(requirements, args.target):
            print(requirements)
    return 0


if __name__ == "__main__":
    sys.exit(main())
