# catkin_python_setup (CMakeLists.txt): the Python package mb_kinematics lives in python/, not at
# the repository root, where the C++ folder mb_kinematics/ would shadow it.
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=["mb_kinematics"], package_dir={"": "python"}))
