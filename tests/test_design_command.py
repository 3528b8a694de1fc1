"""``loader-model design``: output, figure, clear errors, no partial files."""

from __future__ import annotations

from pathlib import Path

import pytest

from loader_model.cli import main


def test_design_prints_gains_costs_and_writes_the_figure(tmp_path: Path, capsys) -> None:
    target = tmp_path / "fig12.png"
    assert main(["design", "--plot", str(target)]) == 0
    out = capsys.readouterr().out
    assert "Table 3 " in out and "unstable" in out and "LQR (empty)" in out
    assert "optimised (ISO 2631)" in out and "loop margin" in out
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fig12.png"]


@pytest.mark.parametrize(
    "arguments, message",
    [
        (["--plot", "fig.pdf"], "suffix '.pdf'"),
        (["--road", "Q"], "road class must be one of"),
        (["--speed", "0"], "--speed 0.0"),
        (["--margin", "-1"], "--margin -1.0"),
    ],
)
def test_design_errors_are_clear_and_write_nothing(
    tmp_path: Path, capsys, monkeypatch, arguments: list[str], message: str
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["design", *arguments]) == 2
    assert message in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []
