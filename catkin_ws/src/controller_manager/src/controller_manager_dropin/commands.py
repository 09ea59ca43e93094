"""`rosrun controller_manager controller_manager <command> [names]`: load, unload, start, stop, spawn (sp),
kill (kl), list (lc), list-types (lt), reload-libraries [--restore], with the output of ros_control's Noetic
controller_manager_interface. Services are relative to the node's namespace (``__ns:=`` or ROS_NAMESPACE)."""
from __future__ import annotations

import sys
from typing import List

import rospy
from controller_manager_msgs.srv import SwitchControllerRequest

from controller_manager_dropin.services import proxy

USAGE = """Commands:
    load <name>          - Load the controller named <name>
    unload <name>        - Unload the controller named <name>
    start <name>         - Start the controller named <name>
    stop <name>          - Stop the controller named <name>
    spawn <name>         - Load and start the controller named <name>
    kill <name>          - Stop and unload the controller named <name>
    list                 - List active controllers
    list-types           - List controller Types
    reload-libraries     - Reloads all plugin controller libraries"""


def list_controller_types() -> None:
    for controller_type in proxy("list_controller_types")().types:
        print(controller_type)


def list_controllers() -> None:
    controllers = proxy("list_controllers")().controller
    if not controllers:
        print("No controllers are loaded in mechanism control")
    for c in controllers:
        interfaces = sorted(set(r.hardware_interface for r in c.claimed_resources))
        print("'%s' - '%s' ( %s )" % (c.name, "+".join(interfaces), c.state))


def load_controller(name: str) -> bool:
    ok = proxy("load_controller")(name).ok
    print(("Loaded '%s'" if ok else "Error when loading '%s'") % name)
    return ok


def unload_controller(name: str) -> bool:
    ok = proxy("unload_controller")(name).ok
    print(("Unloaded '%s' successfully" if ok else "Error when unloading '%s'") % name)
    return ok


def start_stop_controllers(start: List[str], stop: List[str]) -> bool:
    ok = proxy("switch_controller")(start, stop, SwitchControllerRequest.STRICT, False, 0.0).ok
    if not ok:
        print("Error when starting {} and stopping {}".format(start, stop))
    elif start:
        print("Started {} successfully".format(start))
    if ok and stop:
        print("Stopped {} successfully".format(stop))
    return ok


def reload_libraries(restore: bool) -> bool:
    print("Restore: " + str(restore))
    originally = proxy("list_controllers")().controller if restore else []
    ok = proxy("reload_controller_libraries")(True).ok
    print(
        "Successfully reloaded libraries" if ok else "Failed to reload libraries. Do you still have controllers loaded?"
    )
    if restore:
        load = proxy("load_controller")
        for c in originally:
            load(c.name)
        running = [c.name for c in originally if c.state == "running"]
        proxy("switch_controller")(running, [], SwitchControllerRequest.BEST_EFFORT, False, 0.0)
        print("Controllers restored to original state")
    return ok


def run(command: str, names: List[str]) -> None:
    def start(name: str) -> bool:
        return start_stop_controllers([name], [])

    def stop(name: str) -> bool:
        return start_stop_controllers([], [name])

    steps = {
        "load": [load_controller],
        "unload": [unload_controller],
        "start": [start],
        "stop": [stop],
        "spawn": [load_controller, start],
        "kill": [stop, unload_controller],
    }
    command = {"sp": "spawn", "kl": "kill", "lc": "list", "lt": "list-types"}.get(command, command)
    if command == "list-types":
        list_controller_types()
    elif command == "list":
        list_controllers()
    elif command == "reload-libraries":
        reload_libraries("--restore" in names)
    elif command in steps:
        for step in steps[command]:  # each step for every name, then the next step
            for name in names:
                step(name)
    else:
        print(USAGE)
        sys.exit(1)


def main() -> None:
    args = rospy.myargv()
    rospy.init_node("controller_manager", anonymous=True)
    if len(args) < 2:
        print(USAGE)
        sys.exit(0)
    try:
        run(args[1], args[2:])
    except rospy.ROSInterruptException:
        pass
