from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=["joint_state_publisher_gui"], package_dir={"": "src"}))
