"""The wheel's packages, found rather than listed (everything else is in pyproject.toml).

shaders/ and assets/ live at the top level (the design's layout) but travel inside the
package as billiards.shaders and billiards.assets, so a wheel works from any directory.
Every folder under billiards/, shaders/ and assets/ is found, with or without an
__init__.py (assets/scenes holds only data), so a new module or folder cannot be left
out of the wheel by a list nobody updated (tests/test_wheel.py checks the wheel).
"""

from setuptools import find_namespace_packages, setup

# Where each data package's files live in the source tree.
DATA_PACKAGES = {"billiards.shaders": "shaders", "billiards.assets": "assets"}
NOT_PACKAGES = ["*__pycache__*"]


def packages() -> list[str]:
    """billiards and its subpackages, then each data package and its folders."""
    found = find_namespace_packages(include=["billiards", "billiards.*"], exclude=NOT_PACKAGES)
    for package, folder in DATA_PACKAGES.items():
        below = find_namespace_packages(where=folder, exclude=NOT_PACKAGES)
        found += [package, *(f"{package}.{name}" for name in below)]
    return found


setup(packages=packages(), package_dir=DATA_PACKAGES)
