"""The ``loader-model iso2631`` subcommand: report table, weighting plot, errors, no partial file."""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from loader_model import cli
from loader_model.commands import iso2631_command
from loader_model.iso2631 import evaluate_record, plot_weightings, read_vibration_csv

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def parse(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="loader-model iso2631")
    iso2631_command.add_arguments(parser)
    return parser.parse_args(argv)


@pytest.fixture
def seat_csv(tmp_path: Path) -> Path:
    rate_hz = 250.0
    time_s = np.arange(round(8.0 * rate_hz)) / rate_hz
    rng = np.random.default_rng(7)
    table = np.column_stack(
        [
            time_s,
            0.3 * np.sin(2 * np.pi * 1.5 * time_s),
            0.1 * rng.standard_normal(time_s.size),
            9.81 + 0.8 * np.sin(2 * np.pi * 5.0 * time_s),
            0.5 * np.sin(2 * np.pi * 2.0 * time_s),
        ]
    )
    path = tmp_path / "seat.csv"
    np.savetxt(path, table, delimiter=",", header="time,x,y,z,pitch", comments="", fmt="%.10g")
    return path


def test_help_is_one_line_and_heavy_imports_are_deferred() -> None:
    assert "\n" not in iso2631_command.HELP and iso2631_command.HELP
    code = (
        "import sys, loader_model.commands.iso2631_command as c; "
        "print(sorted(m for m in ('numpy', 'control', 'matplotlib', 'scipy') if m in sys.modules))"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == "[]"


def test_report_lists_every_axis_and_the_total(
    seat_csv: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert iso2631_command.run(parse([str(seat_csv), "--exposure-hours", "4"])) == 0
    out = capsys.readouterr().out
    expected = evaluate_record(read_vibration_csv(seat_csv))
    for item in expected.axes:
        assert any(
            line.split()[:4]
            == [item.axis, item.weighting, f"{item.k_factor:.2f}", f"{item.weighted_rms:.4g}"]
            for line in out.splitlines()
        )
    assert f"a_total (paper Eq. 50) = {expected.total_m_s2:.4g} m/s²" in out
    assert "daily exposure A(8)" in out


def test_options_override_weighting_and_k(
    seat_csv: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = [
        str(seat_csv),
        "--weighting",
        "x=Wc",
        "--k-factor",
        "pitch=0.63",
        "--running-rms",
        "exponential",
    ]
    assert iso2631_command.run(parse(argv)) == 0
    out = capsys.readouterr().out
    expected = evaluate_record(
        read_vibration_csv(seat_csv),
        weightings={"x": "Wc"},
        k_factors={"pitch": 0.63},
        running_rms_method="exponential",
    )
    assert f"a_total (paper Eq. 50) = {expected.total_m_s2:.4g} m/s²" in out
    assert any(line.split()[:3] == ["x", "Wc", "1.00"] for line in out.splitlines())


def test_plot_of_the_weightings_is_a_png(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    target = tmp_path / "weightings.png"
    assert iso2631_command.run(parse(["--plot-weightings", str(target)])) == 0
    assert target.read_bytes()[:8] == PNG_SIGNATURE
    assert target.stat().st_size > 10_000
    assert f"wrote {target}" in capsys.readouterr().out
    assert [p.name for p in tmp_path.iterdir()] == ["weightings.png"]  # no temporary left


def test_cli_main_runs_the_command_and_maps_errors_to_exit_2(
    seat_csv: Path,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
) -> None:
    # Only this subcommand, so the test does not depend on the other command modules.
    monkeypatch.setattr(cli, "COMMANDS", {"iso2631": "loader_model.commands.iso2631_command"})
    assert cli.main(["iso2631", str(seat_csv)]) == 0
    bad = tmp_path / "bad.csv"
    bad.write_text("time,z\n0,1\n0.004,nan\n", encoding="utf-8")
    plot = tmp_path / "plot.png"
    assert cli.main(["iso2631", str(bad), "--plot-weightings", str(plot)]) == 2
    assert "column 'z' must be finite; got nan on line 3" in capsys.readouterr().err
    assert not plot.exists()  # a failed command writes no partial output


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        ([], r"give DATA.csv and/or --plot-weightings FILE.png; got neither"),
        (["{csv}", "--k-factor", "z=big"], r"--k-factor z: K must be a number; got 'big'"),
        (["{csv}", "--exposure-hours", "0"], r"--exposure-hours must be in \(0, 24\] .*; got 0.0"),
        (["{csv}", "--exposure-hours", "1e300"], r"--exposure-hours must be in \(0, 24\]"),
        (["{csv}", "--exposure-hours", "nan"], r"--exposure-hours must be in \(0, 24\]"),
        (["{csv}", "--weighting", "roll=We"], r"weightings\['roll'\]: axis 'roll' is not in the"),
        (["{csv}", "--k-factor", "yaw=1"], r"k_factors\['yaw'\]: axis 'yaw' is not in the record"),
        (["{csv}", "--k-factor", "z=1e300"], r"k_factors\['z'\] must be a number in \[0, 2\]"),
        (["{csv}", "--k-factor", "z=1", "--k-factor", "z=2"], r"--k-factor z= is given more"),
        (["{csv}", "--weighting", "z=Wb"], r"weighting must be one of .*; got 'Wb'"),
        (["{csv}", "--weighting", "heave=Wk"], r"weightings axis must be one of .*; got 'heave'"),
        (["{csv}", "--integration-time", "100"], r"integration_time_s must span 1 to 2000 samples"),
        (
            ["--plot-weightings", "{dir}/w.jpg"],
            r"has suffix '\.jpg'; allowed: \['\.png', '\.pdf', '\.svg'\]",
        ),
        (
            ["--plot-weightings", "{dir}/missing/w.png"],
            r"output folder '.*missing' of --plot-weightings '.*w\.png' does not exist",
        ),
    ],
)
def test_bad_invocations_raise_clear_errors(
    seat_csv: Path, tmp_path: Path, argv: list[str], message: str
) -> None:
    args = parse([a.format(csv=seat_csv, dir=tmp_path) for a in argv])
    with pytest.raises(ValueError, match=message):
        iso2631_command.run(args)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["seat.csv"]


def test_malformed_pair_is_an_argparse_error(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_info:
        parse(["data.csv", "--k-factor", "pitch"])
    assert exit_info.value.code == 2
    assert "expected AXIS=VALUE, got 'pitch'" in capsys.readouterr().err


def test_plot_refuses_bad_arguments(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"weighting must be one of .*; got 'Wq'"):
        plot_weightings(tmp_path / "w.png", ["Wk", "Wq"])
    with pytest.raises(ValueError, match=r"weightings must name at least one of .*; got none"):
        plot_weightings(tmp_path / "w.png", [])
    with pytest.raises(
        ValueError, match=r"frequency_range_hz must satisfy 0 < low < high < inf; got \(10, 1\)"
    ):
        plot_weightings(tmp_path / "w.png", frequency_range_hz=(10, 1))
    assert list(tmp_path.iterdir()) == []
