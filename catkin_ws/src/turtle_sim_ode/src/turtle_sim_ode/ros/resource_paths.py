"""Where the simulator may read model and mesh files from, found as gazebo_ros finds them: the ROS package path
(ROS_PACKAGE_PATH, through rospkg), GAZEBO_MODEL_PATH, and the ``<export><gazebo_ros gazebo_model_path="..."/>`` of
every package on the package path (``${prefix}`` is the package's folder; gazebo_ros reads the exports of the
packages that depend on it, this reads them from every package)."""
from __future__ import annotations

import os
from typing import Callable, List, Mapping, Optional

import rospkg
import rospy
from catkin_pkg.package import InvalidPackage

from turtle_sim_ode.models.resources import ResourcePaths

EXPORT_TAG = "gazebo_ros"
MODEL_PATH_ATTRIBUTE = "gazebo_model_path"


def _split(value: Optional[str]) -> List[str]:
    return [entry for entry in (value or "").split(os.pathsep) if entry]


def resource_paths(
    environ: Mapping[str, str] = os.environ, warn: Callable[[str], None] = rospy.logwarn
) -> ResourcePaths:
    """The packages on the package path and the model paths; a package whose manifest cannot be read (catkin_pkg
    refuses its package.xml, a broken manifest.xml) is skipped with one warning naming it, as the simulator still
    runs without it."""
    roots = _split(environ.get("ROS_PACKAGE_PATH"))
    rospack = rospkg.RosPack(roots)
    packages = {}
    model_paths = _split(environ.get("GAZEBO_MODEL_PATH"))
    for name in sorted(rospack.list()):
        try:
            folder = rospack.get_path(name)
            exports = rospack.get_manifest(name).exports
        except rospkg.ResourceNotFound:  # gone since the listing
            continue
        except (rospkg.InvalidManifest, InvalidPackage) as error:
            warn(f"Package '{name}' skipped: its manifest is not valid ({' '.join(str(error).split())})")
            continue
        packages[name] = folder
        for export in exports:
            value = export.get(MODEL_PATH_ATTRIBUTE) if export.tag == EXPORT_TAG else None
            if value:
                model_paths.append(value.replace("${prefix}", folder))
    return ResourcePaths(packages, model_paths, roots + _split(environ.get("GAZEBO_MODEL_PATH")))
