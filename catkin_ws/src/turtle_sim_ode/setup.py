from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

LAYERS = ("physics", "models", "sensors", "world", "ros", "analysis")
setup(
    **generate_distutils_setup(
        packages=["turtle_sim_ode"] + ["turtle_sim_ode." + layer for layer in LAYERS], package_dir={"": "src"}
    )
)
