"""Sensors read from model text and simulated on the physics world: laser, IMU, bumper, cliff, contact."""
