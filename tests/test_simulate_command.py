"""``loader-model simulate``: evaluation printed, files written whole, clear errors, no partial files."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.cli import main


def test_simulate_writes_series_and_plot(tmp_path, capsys) -> None:
    """Single board, passive, 3 s (the weighting filters need 2.6 s): table, CSV, PNG."""
    output = tmp_path / "run.csv"
    code = main(
        ["simulate", "--controller", "passive", "--course", "single", "--speed", "17",
         "--duration", "3", "--output", str(output)]
    )  # fmt: skip
    assert code == 0
    text = capsys.readouterr().out
    assert "vibration total value a_v (paper Eq. 50)" in text and "pitch" in text
    assert "events:" in text
    header = output.read_text().splitlines()[0]
    assert header.startswith("time [s],x_H [m]") and "f_Sy [m/s^2]" in header
    table = np.loadtxt(output, delimiter=",", skiprows=1)
    assert table.shape[0] == 3000 and np.all(np.isfinite(table))
    assert (tmp_path / "run.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["--course", "paper", "--speed", "12"], "paper's speeds"),
        (["--course", "moon"], "--course must be"),
        (["--course", "iso8608:Z"], "road_class"),
        (["--duration", "0"], "--duration"),
        (["--output", "run.txt"], "allowed"),
        (["--load", "no-such-file"], "neither a load case"),
    ],
)
def test_simulate_errors_are_clear(tmp_path, capsys, monkeypatch, arguments, message) -> None:
    """Bad arguments: exit code 2, one line naming the problem, no traceback, no files."""
    monkeypatch.chdir(tmp_path)
    assert main(["simulate", "--output", "out.csv", *arguments]) == 2
    error = capsys.readouterr().err
    assert message in error and "Traceback" not in error
    assert list(tmp_path.iterdir()) == []
