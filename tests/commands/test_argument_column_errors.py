"""Clear errors naming the argument or the column: bound, simulate, identify, robustness.

Each bad input exits with code 2 and one line that names the option (or the column and line)
and what is allowed, before anything is computed.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from loader_model.cli import main
from loader_model.identification.measurement import read_measurement_csv
from tests.robustness.test_robustness_study import TINY


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["bound", "--duration", "inf"], "--duration inf: allowed: a finite time > 0 s"),
        (
            ["bound", "--duration", "2"],
            "--duration 2: allowed: at least 2.6 s (whole --hold-ms intervals over the 2.591 s",
        ),
        (["bound", "--factors", "1,2"], "--factors '1,2': allowed only with --pump-sizing"),
        (
            ["simulate", "--course", "iso8608:C:extra"],
            "--course must be paper, boards, single, iso8608:A to iso8608:H or a course file "
            "FILE.toml; got 'iso8608:C:extra'",
        ),
        (
            ["simulate", "--course", "iso8608:C", "--speed", "1e-9"],
            "--speed 1e-09 km/h: the course takes 7.4e+11 s at that speed; allowed: a drive "
            "of at most 3600 s",
        ),
        (
            ["simulate", "--course", "single", "--speed", "1e-9"],
            "--speed 1e-09 km/h: the course takes",
        ),
        (["simulate", "--speed", "1e-9"], "--speed 1e-09: allowed with --course paper: 9 or 18"),
    ],
)
def test_bad_option_exits_2_naming_it(
    argv: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err, err


def _record(
    path: Path, pressure_unit: str = "Pa", load_kg: float = 340.0, p_a=None, rows: int = 60
) -> Path:
    time = np.arange(rows) * 0.002
    p_a = 1e7 + 1e6 * np.sin(time * 20.0) if p_a is None else p_a
    unit = pressure_unit
    lines = [f"time [s],x_cyl [m],p_A [{unit}],p_B [{unit}],Q_A [m^3/s],m_load [kg]"]
    for t, p in zip(time, p_a, strict=True):
        lines.append(f"{t:.3f},{0.1 + 0.01 * t:.6f},{p:.1f},2.0e6,1e-4,{load_kg}")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_identification_record_errors_name_the_column(tmp_path: Path) -> None:
    assert read_measurement_csv(_record(tmp_path / "ok.csv")).time_s.size == 60
    with pytest.raises(ValueError, match=r"column 'm_load', line 2: -5 kg; allowed: a mass >= 0"):
        read_measurement_csv(_record(tmp_path / "negative.csv", load_kg=-5.0))
    with pytest.raises(
        ValueError, match=r"column 'p_A \[bar\]', line 2: 1e\+12 Pa; allowed: at most 1e\+09 Pa"
    ):
        read_measurement_csv(_record(tmp_path / "bar.csv", pressure_unit="bar"))


def test_constant_signals_name_the_regressors_not_a_singular_matrix(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from loader_model.identification.regression import robust_linear_fit

    constant = _record(tmp_path / "constant.csv", p_a=np.full(400, 1e7), rows=400)
    assert main(["identify", "leakage", str(constant)]) == 2
    err = capsys.readouterr().err
    assert "are linearly dependent (rank" in err and err.count("\n") == 1, err
    design = np.column_stack([np.ones(50), np.full(50, 2.0), np.linspace(0.0, 1.0, 50)])
    with pytest.raises(ValueError, match=r"regressors a, b, c are linearly dependent \(rank 2"):
        robust_linear_fit(design, np.linspace(0.0, 1.0, 50), ["a", "b", "c"])


def test_normal_distribution_mean_outside_its_bounds_is_refused() -> None:
    from loader_model.robustness.study import parse_study

    with pytest.raises(ValueError, match=r"load.mass.mean = 900: allowed: from low to high"):
        parse_study(TINY.replace("mean = 500.0", "mean = 900.0"), "study file")
