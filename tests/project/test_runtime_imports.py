"""The runtime never imports SymPy, and the package works from a regular wheel install."""

from __future__ import annotations

import ast
import os
import subprocess
import sys
import sysconfig
import textwrap
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

USE_THE_MODEL = """
import numpy as np
from loader_model.vehicle.dynamics import LoaderDynamics
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


#: Modules the command line must not load before a command needs them (each costs 0.05-0.6 s).
HEAVY_FOR_THE_CLI = ("matplotlib", "control", "scipy.signal", "casadi", "sympy")


def _loaded_after(code: str, modules: tuple[str, ...] = HEAVY_FOR_THE_CLI) -> list[str]:
    """Which of ``modules`` are in ``sys.modules`` after running ``code`` in a fresh process."""
    result = _run(f"{code}\nimport sys\nprint([m for m in {modules!r} if m in sys.modules])")
    assert result.returncode == 0, result.stderr
    return ast.literal_eval(result.stdout.strip().splitlines()[-1])


def test_cli_import_and_help_load_no_heavy_modules() -> None:
    assert _loaded_after("import loader_model.cli") == []
    help_code = (
        "import contextlib, io\n"
        "import loader_model.cli as cli\n"
        "with contextlib.redirect_stdout(io.StringIO()) as out:\n"
        "    try:\n"
        "        cli.main(['--help'])\n"
        "    except SystemExit as stop:\n"
        "        assert stop.code == 0\n"
        "assert 'simulate' in out.getvalue() and 'iso2631' in out.getvalue()\n"
    )
    assert _loaded_after(help_code, (*HEAVY_FOR_THE_CLI, "numpy", "scipy")) == []


def test_command_modules_import_light() -> None:
    code = (
        "import importlib, loader_model.cli as cli\n"
        "[importlib.import_module(m) for m in cli.COMMANDS.values()]"
    )
    assert _loaded_after(code, (*HEAVY_FOR_THE_CLI, "numpy", "scipy")) == []
    assert _loaded_after("import loader_model.commands.simulate_command") == []


@pytest.mark.parametrize("controller", ["baseline", "skyhook"])
def test_simulate_loads_no_plotting_control_or_scipy_signal(controller: str) -> None:
    """The whole ``simulate`` run (no plot asked for) needs neither matplotlib, python-control
    nor scipy.signal: the ISO 2631-1 weightings run on NumPy, a controller starts at its fixed
    point without its python-control equivalent."""
    code = (
        "import contextlib, io\n"
        "import loader_model.cli as cli\n"
        "with contextlib.redirect_stdout(io.StringIO()) as out:\n"
        f"    assert cli.main(['simulate', '--duration', '3', '--controller', {controller!r}]) == 0\n"
        "assert 'a_total (paper Eq. 50)' in out.getvalue()\n"
    )
    assert _loaded_after(code, ("matplotlib", "control", "scipy.signal", "sympy")) == []


def test_iso2631_evaluation_needs_no_scipy() -> None:
    code = (
        "import numpy as np\n"
        "from loader_model.iso2631 import VibrationRecord, evaluate_record\n"
        "t = np.arange(5000) / 250.0\n"  # 250 Hz: the upsampled path too
        "record = VibrationRecord(time_s=t, axes={'z': np.sin(2 * np.pi * 4 * t)})\n"
        "evaluate_record(record, running_rms_method='exponential')\n"
    )
    assert _loaded_after(code, ("scipy", "control", "matplotlib")) == []


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
