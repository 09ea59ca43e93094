"""The controller manager's services by name, relative to a namespace (controller_manager_msgs' types)."""
from __future__ import annotations

from typing import Any, Optional

import rospy
from controller_manager_msgs.srv import (
    ListControllers,
    ListControllerTypes,
    LoadController,
    ReloadControllerLibraries,
    SwitchController,
    UnloadController,
)

TYPES = {
    "list_controllers": ListControllers,
    "list_controller_types": ListControllerTypes,
    "load_controller": LoadController,
    "unload_controller": UnloadController,
    "switch_controller": SwitchController,
    "reload_controller_libraries": ReloadControllerLibraries,
}


def service_name(name: str, namespace: str = "") -> str:
    """<namespace>/controller_manager/<name>; without a namespace, relative to the node's (as upstream)."""
    if namespace and not namespace.endswith("/"):
        namespace += "/"
    return f"{namespace}controller_manager/{name}"


def proxy(name: str, namespace: str = "", timeout: Optional[float] = None) -> Any:
    """A proxy of the service, once it is there (rospy.ROSException after ``timeout`` seconds)."""
    full = service_name(name, namespace)
    rospy.wait_for_service(full, timeout=timeout)
    return rospy.ServiceProxy(full, TYPES[name])
