"""TurtleBot simulator on ODE with Gazebo's ROS API.

Layers, each importing only from those above it in this list:
physics (ODE world, contacts) -> models (URDF/SDF text to a model description, and bodies built from it) ->
sensors -> world (simulation, Gazebo's world API, plugins, drive) -> ros (the node; the only rospy user).
analysis holds ROS-free helpers for demos and tests (circle fit, trajectory plot, screenshots).
"""
