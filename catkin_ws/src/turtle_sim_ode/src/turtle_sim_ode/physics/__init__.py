"""The physics layer: an ODE world with Gazebo-style contacts, stepped at a fixed rate."""
