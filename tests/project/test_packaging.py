"""What the wheel holds: every package of the tree and every data file, one version everywhere.

The slow test builds the wheel, installs it in a fresh virtual environment outside the checkout
and runs the command line and a derivation from it.
"""

from __future__ import annotations

import fnmatch
import os
import runpy
import subprocess
import sys
import tomllib
import zipfile
from importlib import metadata
from pathlib import Path

import pytest

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


def _run(command: list[str], cwd: Path, timeout_s: float) -> subprocess.CompletedProcess[str]:
    """Run ``command`` in ``cwd`` with the environment of a user outside the checkout."""
    environment = {k: v for k, v in os.environ.items() if k not in {"PYTHONPATH", "VIRTUAL_ENV"}}
    return subprocess.run(
        command, cwd=cwd, env=environment, capture_output=True, text=True, timeout=timeout_s
    )


@pytest.mark.slow
def test_the_wheel_installs_and_runs_outside_the_checkout(tmp_path: Path) -> None:
    """pip wheel, a fresh venv outside the checkout with the wheel and its derive extra (the
    pinned versions), then loader-model --version, reproduce (2 trials a cell) and the
    derivation of the shipped wheel loader's description, byte for byte the shipped code.
    550 s on the 2-core development machine shared with other jobs (the install most of it)."""
    built = _run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "-w", "wheels", str(ROOT)],
        tmp_path,
        300,
    )
    assert built.returncode == 0, built.stderr
    (wheel,) = (tmp_path / "wheels").glob("loader_model-*.whl")
    with zipfile.ZipFile(wheel) as archive:
        names = set(archive.namelist())
    in_wheel = {name.rsplit("/", 1)[0].replace("/", ".") for name in names if "__init__" in name}
    assert in_wheel == source_packages()
    assert source_data_files() <= names

    assert _run([sys.executable, "-m", "venv", "venv"], tmp_path, 120).returncode == 0
    python = tmp_path / "venv" / "bin" / "python"
    lock = ROOT / "requirements-lock.txt"
    install = [str(python), "-m", "pip", "install", "--quiet", "-c", str(lock), f"{wheel}[derive]"]
    installed = _run(install, tmp_path, 1200)
    assert installed.returncode == 0, installed.stderr

    where = _run(
        [str(python), "-c", "import loader_model; print(loader_model.__file__)"], tmp_path, 60
    )
    assert where.stdout.startswith(str(tmp_path / "venv")), where.stdout
    command = str(tmp_path / "venv" / "bin" / "loader-model")
    version = _run([command, "--version"], tmp_path, 60)
    assert version.stdout == f"loader-model {loader_model.__version__}\n", version

    reproduce = [command, "reproduce", "--trials", "2", "--output", "report", "--no-progress"]
    report = _run(reproduce, tmp_path, 1200)
    assert report.returncode == 0, report.stderr[-3000:]
    assert "Table 1" in report.stdout
    assert "Table 6" in (tmp_path / "report" / "report.md").read_text(encoding="utf-8")

    derive = [str(python), "-m", "derive", "--machine", "compact_wheel_loader", "--output", "out"]
    derived = _run(derive, tmp_path, 600)
    assert derived.returncode == 0, derived.stderr
    shipped = ROOT / "generated" / "compact_wheel_loader"
    written = sorted(path.name for path in (tmp_path / "out" / "compact_wheel_loader").glob("*.py"))
    assert written == sorted(path.name for path in shipped.glob("*.py"))
    for name in written:
        text = (tmp_path / "out" / "compact_wheel_loader" / name).read_bytes()
        assert text == (shipped / name).read_bytes(), name
