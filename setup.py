# catkin_python_setup(): exposes the Python package offshore_gnc (test harness, report tools).
from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=["offshore_gnc", "offshore_gnc.ardusub", "offshore_gnc.campaign",
                                           "offshore_gnc.testing"], package_dir={"": "python"}))
