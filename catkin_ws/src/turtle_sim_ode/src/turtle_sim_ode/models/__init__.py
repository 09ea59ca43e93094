"""Model text (URDF, SDF) to a model description, and the ODE bodies and joints built from it."""
