from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import find_packages, setup

# turtle_sim_ode and its layers (physics, models, sensors, world, ros, analysis) with their subpackages (plugins).
setup(**generate_distutils_setup(packages=find_packages("src"), package_dir={"": "src"}))
