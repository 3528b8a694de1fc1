"""Which packages the wheel holds, found from the source tree so that a new one cannot be missed.

Everything else about the build is in ``pyproject.toml``. ``[tool.setuptools.packages.find]``
cannot rename a folder, and the generated code lives in ``generated/`` but installs as
``loader_model_generated``: this file finds the packages of both.
"""

from setuptools import find_packages, setup

GENERATED = "loader_model_generated"


def packages() -> list[str]:
    """Every package of loader_model and derive, and generated/ as loader_model_generated."""
    found = find_packages(include=["loader_model", "loader_model.*", "derive", "derive.*"])
    return [*found, GENERATED, *(f"{GENERATED}.{name}" for name in find_packages("generated"))]


if __name__ == "__main__":  # run by the build backend (and `python setup.py`)
    setup(packages=packages(), package_dir={GENERATED: "generated"})
