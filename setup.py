# The Python client of the node's services (spatial_dynamics.client); catkin_python_setup() in
# CMakeLists.txt installs it, beside the generated service modules (spatial_dynamics.srv).
# Not for running by hand: catkin calls it.
from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(
    packages=['spatial_dynamics'],
    package_dir={'': 'src'},
))
