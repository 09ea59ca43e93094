"""`rosrun controller_manager unspawner name...`: stops the named controllers while it runs (again every 3 s, should
something start them) and starts them again when it is shut down, as ros_control's Noetic unspawner."""
from __future__ import annotations

import sys
from typing import Set

import rospy
from controller_manager_msgs.srv import SwitchControllerRequest

from controller_manager_dropin.services import proxy

HELP = """./unspawner name1 name2 name3

\tStops a set of controllers until killed.
\tUseful in roslaunch files to temporarily stop controllers"""


def main() -> None:
    argv = rospy.myargv()
    if len(argv) == 1 or argv[1] in ("-h", "--help"):
        print(HELP)
        sys.exit(1)
    rospy.init_node("unspawner", anonymous=True)
    switch = proxy("switch_controller")
    list_controllers = proxy("list_controllers")
    to_inhibit = set(argv[1:])
    inhibited: Set[str] = set()

    def stop_controllers(_event: object = None) -> None:
        running = {c.name for c in list_controllers().controller if c.state == "running"}
        to_stop = to_inhibit & running
        if to_stop:
            # remembered before the switch: a shutdown during it restarts them
            inhibited.update(to_stop)
            switch([], sorted(to_stop), SwitchControllerRequest.BEST_EFFORT, False, 0.0)
            rospy.loginfo("Inhibiting controllers: %s" % ", ".join(sorted(to_stop)))

    timers = []

    def restart_controllers() -> None:
        for timer in timers:
            timer.shutdown()
        switch(sorted(inhibited), [], SwitchControllerRequest.BEST_EFFORT, False, 0.0)

    # registered before the first stop, so that a shutdown at any moment after it restarts what was stopped
    rospy.on_shutdown(restart_controllers)
    stop_controllers()
    timers.append(rospy.Timer(rospy.Duration(3), stop_controllers))
    rospy.spin()
