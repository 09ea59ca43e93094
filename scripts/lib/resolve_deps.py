#!/usr/bin/env python3
"""Print the system packages the workspace needs on one platform.

The dependency list is the packages' own package.xml files: every key they name (minus the workspace's own
packages) is mapped to system packages through rosdeps.tsv, plus the "tool:" rows the scripts need. A workspace
package that has a row of its own is a drop-in for a system package (scripts/lib/dropins.py): its key is resolved
through that row, so that a platform that has the real package installs it. Only the standard library is used,
so this runs before anything is installed.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
DEPEND_TAGS = ("depend", "build_depend", "build_export_depend", "exec_depend", "test_depend", "buildtool_depend")
PLATFORMS = ("debian", "ubuntu")


def load_table(path):
    table = {}
    with open(path) as table_file:
        for line in table_file:
            if not line.strip() or line.startswith("#"):
                continue
            key, debian, ubuntu = line.rstrip("\n").split("\t")
            if ubuntu == "-":
                ubuntu = "ros-noetic-" + key.replace("_", "-")
            elif ubuntu == "=":
                ubuntu = debian
            table[key] = {"debian": debian.split(), "ubuntu": ubuntu.split()}
    return table


def workspace_keys(src_dir):
    """Return (own package names, dependency keys) found in every package.xml below src_dir."""
    own, keys = set(), set()
    for root, dirs, files in os.walk(src_dir):
        dirs[:] = [d for d in dirs if not d.startswith(".")]
        if "package.xml" in files:
            tree = ET.parse(os.path.join(root, "package.xml"))
            own.add(tree.findtext("name").strip())
            for tag in DEPEND_TAGS:
                keys.update(element.text.strip() for element in tree.iter(tag))
    return own, keys


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--platform", choices=PLATFORMS, required=True)
    parser.add_argument("--src", default=os.path.join(HERE, "..", "..", "catkin_ws", "src"))
    args = parser.parse_args()

    table = load_table(os.path.join(HERE, "rosdeps.tsv"))
    own, keys = workspace_keys(args.src)
    keys -= {name for name in own if name not in table}
    unknown = sorted(k for k in keys if k not in table)
    if unknown:
        sys.exit(
            "resolve_deps: no system package known for rosdep key(s) %s: add them to %s"
            % (", ".join(unknown), os.path.join(HERE, "rosdeps.tsv"))
        )
    keys.update(k for k in table if k.startswith("tool:"))
    packages = sorted({p for k in keys for p in table[k][args.platform]})
    print("\n".join(packages))


if __name__ == "__main__":
    main()
