"""Files a model or world names (model://, package://, file:// URIs: meshes, included models), read only from under
the roots they may come from: the ROS package path and Gazebo's model path. No other file is ever opened.

A path that leaves its roots (``..``, a symlink pointing out), or is not a regular file (a FIFO, a device, /proc
entries, which report no size) or is larger than MAX_RESOURCE_BYTES, is refused with a ResourceError naming it.
Where the paths come from (ROS_PACKAGE_PATH, GAZEBO_MODEL_PATH, the packages' <export><gazebo_ros
gazebo_model_path="..."/>) is the ROS layer's business (ros.resource_paths)."""
from __future__ import annotations

import os
import stat
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

from turtle_sim_ode.models.text import ModelError

# Far beyond any mesh or model file a robot description uses (TurtleBot3's largest mesh is ~3 MB).
MAX_RESOURCE_BYTES = 64 * 1024 * 1024
# The procfs and sysfs report files of size 0 that are not what they seem; never read from them even if a root
# points there.
_FORBIDDEN_PREFIXES = ("/proc", "/sys", "/dev")


class ResourceError(ModelError):
    """A file named by a model or world cannot or may not be read."""


def _real(path: str) -> str:
    return os.path.realpath(os.path.abspath(path))


def _under(path: str, root: str) -> bool:
    return path == root or path.startswith(root.rstrip(os.sep) + os.sep)


@dataclass
class ResourcePaths:
    """``packages``: ROS package name -> its folder; ``model_paths``: Gazebo model path entries (folders holding
    one folder per model), in search order; ``roots``: the folders files may be read from (the ROS package path
    entries and the model path entries; the packages' own folders are added)."""

    packages: Dict[str, str] = field(default_factory=dict)
    model_paths: List[str] = field(default_factory=list)
    roots: List[str] = field(default_factory=list)

    def allowed_roots(self) -> List[str]:
        found = [_real(root) for root in list(self.roots) + list(self.model_paths) + list(self.packages.values())]
        return [root for root in dict.fromkeys(found) if not any(_under(root, bad) for bad in _FORBIDDEN_PREFIXES)]

    def model_folder(self, name: str) -> Optional[str]:
        """The folder of Gazebo model ``name`` (first on the model path), or None."""
        if not name or name in (".", "..") or "/" in name:
            return None
        for entry in self.model_paths:
            candidate = os.path.join(entry, name)
            if os.path.isdir(candidate):
                return candidate
        return None

    def resolve(self, uri: str, base: Optional[str] = None) -> str:
        """The file path a URI names: ``model://NAME/rest`` on the model path, ``package://PKG/rest`` in the
        package's folder, ``file:///abs`` or a plain path (relative ones to ``base``); ResourceError if the model
        or package is unknown. Whether it may be read is read_resource's to say."""
        if uri.startswith("model://"):
            name, _, rest = uri[len("model://") :].partition("/")
            folder = self.model_folder(name)
            if folder is None:
                raise ResourceError(f"cannot resolve {uri}: no model '{name}' on the model path {self.model_paths}")
            return os.path.join(folder, rest)
        if uri.startswith("package://"):
            package, _, rest = uri[len("package://") :].partition("/")
            folder = self.packages.get(package)
            if folder is None:
                raise ResourceError(f"cannot resolve {uri}: no package '{package}' on the ROS package path")
            return os.path.join(folder, rest)
        if uri.startswith("file://"):
            return uri[len("file://") :]
        if "://" in uri:
            raise ResourceError(f"cannot resolve {uri}: unsupported URI scheme")
        return uri if os.path.isabs(uri) or base is None else os.path.join(base, uri)

    def read(self, uri: str, base: Optional[str] = None, limit: int = MAX_RESOURCE_BYTES) -> Tuple[str, bytes]:
        """(path, contents) of the file ``uri`` names, read as read_resource reads it."""
        path = self.resolve(uri, base)
        return path, read_resource(path, self.allowed_roots(), limit, uri)


def read_resource(path: str, roots: Sequence[str], limit: int = MAX_RESOURCE_BYTES, name: str = "") -> bytes:
    """The contents of regular file ``path`` if it lies, symlinks resolved, under one of ``roots`` and holds at most
    ``limit`` bytes; ResourceError naming it (``name``, else the path) otherwise. Opened without following a final
    symlink and without blocking (a FIFO swapped in after the checks is refused by fstat, not waited on)."""
    what = name or path
    real = _real(path)
    if not roots:
        raise ResourceError(f"'{what}' is not read: no ROS package path or Gazebo model path to read files from")
    if not any(_under(real, root) for root in roots):
        raise ResourceError(f"'{what}' ({real}) is outside the ROS package path and the model path: not read")
    try:
        descriptor = os.open(real, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as error:
        raise ResourceError(f"'{what}' cannot be opened: {error.strerror}") from None
    try:
        status = os.fstat(descriptor)
        if not stat.S_ISREG(status.st_mode):
            raise ResourceError(f"'{what}' is not a regular file: not read")
        if status.st_size > limit:
            raise ResourceError(f"'{what}' is {status.st_size} bytes, more than the {limit} allowed")
        chunks = []
        total = 0
        while True:
            chunk = os.read(descriptor, min(1 << 20, limit + 1 - total))
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
            if total > limit:
                raise ResourceError(f"'{what}' grew beyond the {limit} bytes allowed while read")
        return b"".join(chunks)
    except OSError as error:
        raise ResourceError(f"'{what}' cannot be read: {error.strerror}") from None
    finally:
        os.close(descriptor)
