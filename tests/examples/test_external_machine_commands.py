"""A machine described outside the package runs every command that builds a model.

The tractor of docs/examples/tractor_front_loader.md (its own tyres per axle, the pump-controlled
lift circuit, a cab on a sliding mount that carries the seat), under a name of its own (the
package ships the same machine as ``tractor_front_loader``) and derived into the session's
temporary cache, given to each command by ``--machine FILE --params FILE`` (or the study file's
``machine`` and ``params``): each ends with its exit code for a run (0; the design check's 4 for
a design that fails it) and prints or writes what it is for. The commands that reproduce the
paper (``reproduce``, ``calibrate``, ``calibrate-table6``, ``fidelity``) are the skid-steer's by
their purpose and refuse another machine in one line (their own tests).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from loader_model.cli import main
from loader_model.commands.check_design_command import EXIT_CHECK_FAILED
from tests.examples.test_tractor_front_loader import machine_args

#: Deriving with SymPy about 10 s, then a few seconds per command (2-core machine).
pytestmark = pytest.mark.slow

__all__ = ["machine_args"]  # the module fixture, shared with the example's own tests


def _run(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    code = main(argv)
    return code, capsys.readouterr().out


def test_model_modes_and_hydraulics(machine_args: list[str], tmp_path: Path, capsys) -> None:
    code, out = _run(["model", *machine_args, "--load", "full"], capsys)
    assert code == 0 and "Static equilibrium" in out and "F_Ay0" in out
    code, out = _run(["modes", *machine_args, "--load", "full"], capsys)
    assert code == 0 and "Hz" in out
    plot = tmp_path / "pressure_loop.png"
    code, out = _run(["hydraulics", *machine_args, "--load", "empty", "--plot", str(plot)], capsys)
    assert code == 0 and "bar" in out and plot.stat().st_size > 0


def test_simulate_and_export_fmu(machine_args: list[str], tmp_path: Path, capsys) -> None:
    run = tmp_path / "run.csv"
    argv = ["simulate", *machine_args, "--load", "full", "--controller", "skyhook"]
    code, out = _run([*argv, "--duration", "3", "--output", str(run)], capsys)
    assert code == 0 and "a_total" in out and run.stat().st_size > 0
    fmu = tmp_path / "tractor.fmu"
    code, _ = _run(["export-fmu", *machine_args, "--load", "full", str(fmu)], capsys)
    assert code == 0 and fmu.stat().st_size > 0


def test_design_and_its_check(machine_args: list[str], tmp_path: Path, capsys) -> None:
    gains = tmp_path / "gains.toml"
    argv = ["design", *machine_args, "--method", "lqr", "--no-check", "--force"]
    code, out = _run([*argv, "--output", str(gains)], capsys)
    assert code == 0 and gains.is_file()
    conditions = tmp_path / "conditions.toml"
    conditions.write_text(
        '[envelope]\nloads = ["empty"]\nboard_speeds_kmh = []\nroad_classes = ["C"]\n'
        "road_speeds_kmh = [15.0]\n[criteria]\nsampled_plants = 0\n",
        encoding="utf-8",
    )
    argv = ["check-design", str(gains), *machine_args, "--conditions", str(conditions)]
    code, out = _run([*argv, "--jobs", "1", "--no-progress"], capsys)
    assert code in (0, EXIT_CHECK_FAILED) and "1 judged condition" in out.replace(
        "conditions", "condition"
    )


def test_robustness_study(tmp_path: Path, capsys, machine_args: list[str]) -> None:
    study = tmp_path / "study.toml"
    study.write_text(
        f'[study]\nname = "tractor"\nmachine = "{Path(machine_args[1]).as_posix()}"\n'
        f'params = "{Path(machine_args[3]).as_posix()}"\nseed = 1\nsamples = 2\nduration_s = 3.0\n'
        'batch_size = 2\n[conditions]\nspeeds_kmh = [9.0]\n[controllers]\ncompare = ["skyhook"]\n'
        '[parameters]\n"hydraulics.bulk_modulus" = { distribution = "uniform", low = 0.8e9, '
        'high = 1.8e9, unit = "Pa" }\n',
        encoding="utf-8",
    )
    out_dir = tmp_path / "study"
    argv = ["robustness", str(study), "--output", str(out_dir), "--jobs", "1", "--no-progress"]
    code, _ = _run(argv, capsys)
    assert code == 0 and any(out_dir.iterdir())


def test_bound_and_preview(machine_args: list[str], capsys) -> None:
    argv = ["bound", *machine_args, "--speed", "9", "--load", "empty", "--duration", "3"]
    code, out = _run([*argv, "--no-progress"], capsys)
    assert code == 0 and "bound" in out
    code, out = _run(["preview", *machine_args, "--no-progress"], capsys)
    assert code == 0 and "preview" in out
