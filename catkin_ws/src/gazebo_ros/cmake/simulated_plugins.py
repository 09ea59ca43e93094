"""Prints the plugin file names turtle_sim_ode simulates (model and sensor plugins) as a CMake list, for the gazebo
stand-in (gazebo_standin.cmake); prints nothing where turtle_sim_ode cannot be imported. Argument: a folder to
import turtle_sim_ode from first (its sources beside gazebo_ros), used where it exists."""
import os
import sys

if len(sys.argv) > 1 and os.path.isdir(os.path.join(sys.argv[1], "turtle_sim_ode")):
    sys.path.insert(0, sys.argv[1])
try:
    from turtle_sim_ode.sensors.plugins import SENSOR_PLUGINS
    from turtle_sim_ode.world.plugins import MODEL_PLUGINS
except ImportError as error:
    sys.stderr.write("turtle_sim_ode's plugin list is not available (%s); " % error)
else:
    sys.stdout.write(";".join(sorted(set(MODEL_PLUGINS) | set(SENSOR_PLUGINS))))
