"""The runtime never imports SymPy, and the package works from a regular wheel install."""

from __future__ import annotations

import os
import subprocess
import sys
import sysconfig
import textwrap
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

USE_THE_MODEL = """
import numpy as np
from loader_model.dynamics import LoaderDynamics
from tests.conftest import PAPER_LAYOUT
model = LoaderDynamics(PAPER_LAYOUT)
linear = model.linearise()
assert linear.A.shape == (8, 8)
assert np.all(np.isfinite(model.forward_dynamics(np.zeros(4), np.zeros(4))))
linear.state_space()
"""


def _run(code: str, **kwargs: object) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, *kwargs.pop("flags", []), "-c", code],  # type: ignore[misc]
        capture_output=True,
        text=True,
        cwd=kwargs.pop("cwd", ROOT),  # type: ignore[arg-type]
        env={**os.environ, **kwargs.pop("env", {})},  # type: ignore[dict-item]
        check=False,
    )


def test_runtime_works_with_sympy_blocked() -> None:
    blocker = textwrap.dedent(
        """
        import sys
        sys.modules["sympy"] = None  # any `import sympy` now raises ImportError
        """
    )
    result = _run(
        blocker
        + USE_THE_MODEL
        + "\nassert 'sympy' not in [m for m in sys.modules if sys.modules[m]]"
    )
    assert result.returncode == 0, result.stderr


def test_import_loader_model_loads_no_heavy_modules() -> None:
    code = (
        "import sys, loader_model\n"
        "heavy = [m for m in ('sympy', 'casadi', 'control', 'scipy', 'matplotlib') if m in sys.modules]\n"
        "print(heavy)\n"
    )
    result = _run(code)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "[]"


@pytest.mark.slow
def test_wheel_install_imports_generated_package(tmp_path: Path) -> None:
    """Build a wheel, unpack it and import from it without the editable-install finder."""
    build = subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            "--no-deps",
            "--quiet",
            "-w",
            str(tmp_path),
            str(ROOT),
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    assert build.returncode == 0, build.stderr
    (wheel,) = tmp_path.glob("loader_model-*.whl")
    unpacked = tmp_path / "unpacked"
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
        archive.extractall(unpacked)
    assert any(n.startswith("loader_model_generated/mass_matrix.py") for n in names)
    site_packages = sysconfig.get_paths()["purelib"]
    code = (
        f"import sys; sys.path[:0] = [{str(unpacked)!r}, {site_packages!r}, {str(ROOT)!r}]\n"
        "import loader_model, loader_model_generated\n"
        f"assert loader_model.__file__.startswith({str(unpacked)!r}), loader_model.__file__\n"
        f"assert loader_model_generated.__file__.startswith({str(unpacked)!r})\n" + USE_THE_MODEL
    )
    # -S: no site processing, so the editable install's path hook in site-packages stays off.
    result = _run(code, flags=["-S"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
