"""What the wheel holds: every package of the tree and every data file, one version everywhere.

The slow test builds the wheel, installs it in a fresh virtual environment outside the checkout
and runs the command line and a derivation from it.
"""

from __future__ import annotations

import fnmatch
import runpy
import tomllib
from importlib import metadata
from pathlib import Path

import loader_model

ROOT = Path(__file__).resolve().parents[2]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
#: Source folder -> the package it installs as.
TREES = {"loader_model": "loader_model", "derive": "derive", "generated": "loader_model_generated"}


def source_packages() -> set[str]:
    """Every folder with an ``__init__.py`` under the three trees, as a package name."""
    names = set()
    for folder, package in TREES.items():
        for init in (ROOT / folder).rglob("__init__.py"):
            parts = init.parent.relative_to(ROOT / folder).parts
            if "__pycache__" not in parts:
                names.add(".".join((package, *parts)))
    return names


def source_data_files() -> set[str]:
    """Every file under the trees that is not Python source or a byte-code cache, as the path
    it installs at (``loader_model/data/default_loader.toml``)."""
    files = set()
    for folder, package in TREES.items():
        for path in (ROOT / folder).rglob("*"):
            relative = path.relative_to(ROOT / folder)
            if path.is_file() and path.suffix not in {".py", ".pyc"}:
                if "__pycache__" not in relative.parts:
                    files.add(f"{package.replace('.', '/')}/{relative.as_posix()}")
    return files


def test_setup_finds_every_package_of_the_tree() -> None:
    found = runpy.run_path(str(ROOT / "setup.py"), run_name="setup_packages")["packages"]()
    assert sorted(found) == sorted(source_packages())
    assert "loader_model.bound" in found and "derive" in found


def test_every_data_file_is_package_data() -> None:
    """Each data file beside the packages (data, FMU sources, machine descriptions, py.typed)
    matches a pattern of [tool.setuptools.package-data], so the wheel ships it."""
    patterns = PYPROJECT["tool"]["setuptools"]["package-data"]
    missing = []
    for path in sorted(source_data_files()):
        package, _, inside = path.partition("/")
        if not any(fnmatch.fnmatch(inside, pattern) for pattern in patterns.get(package, [])):
            missing.append(path)
    assert missing == []
    assert "loader_model/py.typed" in source_data_files()
    assert "derive/machines/skid_steer.toml" in source_data_files()


def test_one_version_everywhere() -> None:
    version = PYPROJECT["project"]["version"]
    assert metadata.version("loader-model") == loader_model.__version__ == version
    citation = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    assert f"\nversion: {version}\n" in citation
    assert f"\n## {version} " in (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")


def test_licence_and_citation() -> None:
    assert PYPROJECT["project"]["license"] == "MIT"
    assert (ROOT / "LICENSE").read_text(encoding="utf-8").startswith("MIT License\n")
    citation = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    for field in ("cff-version: 1.2.0", "preferred-citation:", "family-names: Williamson",
                  "journal: \"International Journal of Fluid Power\"", "volume: 10", "issue: 3",
                  "year: 2009"):  # fmt: skip
        assert field in citation, field
