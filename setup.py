"""Packages: antenna_cad and its subpackages, plus the top-level recipes/ folder installed as the data
package antenna_cad.recipes (so a clone keeps recipes/ where tests and users expect it). Everything
else is in pyproject.toml."""

from setuptools import find_packages, setup

setup(packages=find_packages(include=["antenna_cad", "antenna_cad.*"]) + ["antenna_cad.recipes"],
      package_dir={"antenna_cad.recipes": "recipes"},
      package_data={"antenna_cad.recipes": ["*.yaml", "sweeps/*.yaml"],
                    "antenna_cad.export": ["viewer/*.js", "viewer/LICENSE-three.txt"],   # the report's 3-D viewer
                    "antenna_cad.printed": ["data/*.csv"]})                               # the homogenization table
