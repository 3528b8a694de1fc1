"""``loader-model identify``: synthesize, fit, print beside the tables, plot, update; errors."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from loader_model.cli import main


@pytest.fixture(scope="module")
def data(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("identify") / "lift.csv"
    # A short record (3 cycles at 200 Hz) keeps the test fast; accuracy is tested elsewhere.
    assert main(["identify", "synthesize", str(path), "--cycles", "3", "--sample-rate", "200"]) == 0
    return path


def test_synthesize_writes_a_labelled_csv(data: Path) -> None:
    lines = data.read_text().splitlines()
    assert lines[0].startswith("# synthetic lift test")
    header = next(line for line in lines if not line.startswith("#"))
    assert header == (
        "time [s],x_cyl [m],p_A [Pa],p_B [Pa],Q_A [m^3/s],m_load [kg],"
        "theta_1 [rad],f_Hx [m/s^2],f_Hy [m/s^2],f_Ny [m/s^2]"
    )


def test_friction_prints_table_4_and_writes_plot(
    data: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    plot = tmp_path / "fit.png"
    assert main(["identify", "friction", str(data), "--plot", str(plot)]) == 0
    out = capsys.readouterr().out
    for text in ("Table 4", "f_s", "tau_s", "gamma", "N/bar", "kN·s/m", "R²", "95% interval"):
        assert text in out
    assert "the boom on the moving chassis" in out
    assert plot.stat().st_size > 10_000


def test_friction_update_writes_the_identified_values_with_their_source(
    data: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    update = tmp_path / "loader.toml"
    assert main(["identify", "friction", str(data), "--update", str(update)]) == 0
    raw = tomllib.loads(update.read_text())
    for name in ("f_s", "tau_s", "gamma", "f_c", "f_v"):
        assert raw["friction"][name]["source"].startswith(f"identified from {data.name}")
    assert "wrote" in capsys.readouterr().out


@pytest.mark.slow  # 5 s (a whole identification run before the refusal)
def test_friction_update_out_of_range_is_refused_and_writes_nothing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Without the chassis columns Eq. 44 takes the chassis at rest; on this short record the
    # fit leaves the parameter file's ranges, which the update refuses.
    data = tmp_path / "rest.csv"
    argv = ["identify", "synthesize", str(data), "--cycles", "3", "--sample-rate", "200"]
    assert main([*argv, "--no-chassis"]) == 0
    update, plot = tmp_path / "loader.toml", tmp_path / "fit.png"
    argv = ["identify", "friction", str(data), "--update", str(update), "--plot", str(plot)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "friction.f_s = " in err and "out of range" in err
    assert "Traceback" not in err
    assert list(tmp_path.iterdir()) == [data]


def test_leakage_prints_table_5_and_updates_leakage_and_bulk_modulus(
    data: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    update = tmp_path / "loader.toml"
    assert main(["identify", "leakage", str(data), "--update", str(update)]) == 0
    out = capsys.readouterr().out
    for text in ("Table 5", "K_oil", "k_Lp", "k_Lv", "bisquare", "m³/s"):
        assert text in out
    raw = tomllib.loads(update.read_text())
    for section, name in (("leakage", "k_lp"), ("leakage", "k_lv"), ("hydraulics", "bulk_modulus")):
        assert raw[section][name]["source"].startswith(f"identified from {data.name}")
    assert main(["identify", "leakage", str(data), "--least-squares"]) == 0
    assert "least squares" in capsys.readouterr().out


def test_bad_csv_gives_a_clear_error_and_writes_nothing(
    data: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    lines = data.read_text().splitlines()
    cells = lines[10].split(",")
    cells[1] = "oops"  # x_cyl on file line 11
    lines[10] = ",".join(cells)
    bad = tmp_path / "bad.csv"
    bad.write_text("\n".join(lines) + "\n")
    update, plot = tmp_path / "new.toml", tmp_path / "fit.png"
    argv = ["identify", "friction", str(bad), "--update", str(update), "--plot", str(plot)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "loader-model identify: error:" in err
    assert "column 'x_cyl', line 11: 'oops' is not a number" in err
    assert "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.csv"]


def test_missing_output_folder_and_bad_options_are_reported(
    data: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    missing = tmp_path / "nowhere" / "x.toml"
    assert main(["identify", "friction", str(data), "--update", str(missing)]) == 2
    assert "does not exist" in capsys.readouterr().err
    assert main(["identify", "friction", str(data), "--level", "1.5"]) == 2
    assert "--level" in capsys.readouterr().err
    assert main(["identify", "synthesize", str(missing)]) == 2
    assert not missing.parent.exists()
