"""Noetic's `xacro` command on PyPI's xacro library, with `$(find pkg)` resolved through the ROS package path.

PyPI's xacro (the upstream project's ROS 2 line) resolves `$(find pkg)` through ament_index, which knows no
catkin package. Noetic's xacro resolves it with rospack: the package's directory on ROS_PACKAGE_PATH. The
library looks the resolver up as `xacro.substitution_args._eval_find` (for `$(find pkg)`) and in
`_eval_dict["find"]` (for `$(eval find('pkg'))`); `use_ros_package_path` replaces both. Expressions are
evaluated in a sandbox (sandbox.py).
"""
from __future__ import annotations

import os
import sys
from types import ModuleType
from typing import Callable, List, Optional

import rospkg

from xacro_dropin.sandbox import sandbox_xacro

PYPI_DIR_ENV = "XACRO_PYPI_DIR"
DEFAULT_PYPI_DIR = "/usr/local/lib/ros_dropins/python"


class PackageNotFound(Exception):
    """`$(find pkg)` named a package that is not on the ROS package path."""


def pypi_dir() -> str:
    """Where scripts/install_deps.sh puts PyPI's xacro (`$XACRO_PYPI_DIR` overrides)."""
    return os.environ.get(PYPI_DIR_ENV) or DEFAULT_PYPI_DIR


def ros_package_finder(rospack: rospkg.RosPack) -> Callable[[str], str]:
    """A `find(package) -> directory` that answers as `rospack find` does, with a clear error otherwise."""

    def find(package: str) -> str:
        try:
            return rospack.get_path(package)
        except rospkg.ResourceNotFound:
            search_path = os.environ.get("ROS_PACKAGE_PATH", "")
            raise PackageNotFound(
                "$(find %s): package '%s' not found on the ROS package path [ROS_PACKAGE_PATH=%s]"
                % (package, package, search_path)
            ) from None

    return find


def use_ros_package_path(substitution_args: ModuleType, find: Callable[[str], str]) -> None:
    """Make the library's `$(find pkg)` and `$(eval find('pkg'))` call `find`."""
    if not hasattr(substitution_args, "_eval_find") or "find" not in getattr(substitution_args, "_eval_dict", {}):
        raise RuntimeError(
            "%s has no _eval_find/_eval_dict hook: not the PyPI xacro this drop-in was written for"
            % getattr(substitution_args, "__file__", substitution_args)
        )
    substitution_args._eval_find = find
    substitution_args._eval_dict["find"] = find


def import_pypi_xacro(directory: Optional[str] = None) -> ModuleType:
    """Import PyPI's xacro, from `directory` (default: pypi_dir()) if it holds it, else from sys.path."""
    directory = directory or pypi_dir()
    if os.path.isdir(os.path.join(directory, "xacro")) and directory not in sys.path:
        sys.path.insert(0, directory)
    import xacro

    if getattr(xacro, "__file__", None) is None:  # a directory named xacro on sys.path, not the library
        raise ImportError("'xacro' resolves to %s, which is no module" % list(getattr(xacro, "__path__", [])))
    return xacro


def main(argv: Optional[List[str]] = None) -> int:
    """`xacro [options] input [arg:=value ...]`, as Noetic's (`--inorder` is accepted with a note)."""
    argv = sys.argv[1:] if argv is None else argv
    try:
        xacro = import_pypi_xacro()
        from xacro import substitution_args
    except ImportError as error:
        sys.stderr.write(
            "xacro: PyPI's xacro library is not installed (%s; looked in %s): run scripts/install_deps.sh\n"
            % (error, pypi_dir())
        )
        return 1
    use_ros_package_path(substitution_args, ros_package_finder(rospkg.RosPack()))
    sandbox_xacro(xacro, substitution_args)  # expressions in the files never run commands (see sandbox.py)
    # xacro 2.1.1 names xml.parsers.expat in an except clause without importing it: an input file that cannot be
    # opened would end in an AttributeError instead of its error message and exit code 2.
    import xml.parsers.expat  # noqa: F401

    sys.argv = ["xacro"] + list(argv)
    xacro.main()  # exits 2 with the error on stderr when processing fails
    return 0
