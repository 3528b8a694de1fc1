"""The pinned set: requirements-lock.txt pins every dependency of pyproject.toml exactly, and the
environment the tests run in is that set (so a fresh machine resolves nothing of its own)."""

from __future__ import annotations

import re
import tomllib
from importlib import metadata
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
LOCK = ROOT / "requirements-lock.txt"


def _canonical(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def _pins() -> dict[str, str]:
    pins = {}
    for number, line in enumerate(LOCK.read_text(encoding="utf-8").splitlines(), start=1):
        if not line.strip() or line.startswith("#"):
            continue
        match = re.fullmatch(r"([A-Za-z0-9][A-Za-z0-9._-]*)==([A-Za-z0-9.+!-]+)", line.strip())
        assert match, f"{LOCK.name} line {number} is not an exact pin: {line!r}"
        pins[_canonical(match[1])] = match[2]
    return pins


def test_every_declared_dependency_is_pinned() -> None:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    declared = list(project["dependencies"])
    for extra in project["optional-dependencies"].values():
        declared.extend(extra)
    names = {_canonical(re.match(r"[A-Za-z0-9._-]+", spec)[0]) for spec in declared}
    missing = sorted(names - set(_pins()))
    assert not missing, f"not pinned in {LOCK.name}: {missing} (run `make lock`)"


def test_installed_versions_are_the_pinned_ones() -> None:
    wrong = {}
    for name, version in _pins().items():
        try:
            installed = metadata.version(name)
        except metadata.PackageNotFoundError:
            wrong[name] = (version, "not installed")
            continue
        if installed != version:
            wrong[name] = (version, installed)
    if wrong:
        pytest.fail(f"environment differs from {LOCK.name} (pinned, installed): {wrong}")
