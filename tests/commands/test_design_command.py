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


def test_designed_gains_go_to_a_settings_file_that_simulate_runs(tmp_path: Path, capsys) -> None:
    from loader_model.control.settings import load_settings

    target = tmp_path / "designed.toml"
    assert main(["design", "--load", "empty", "--solver", "ipopt", "--output", str(target)]) == 0
    out = capsys.readouterr().out
    settings = load_settings(target)
    printed = next(line for line in out.splitlines() if "optimised (ISO 2631) " in line)
    shown = [float(v) for v in printed.split("[")[1].split("]")[0].split()]
    assert shown == pytest.approx(settings.k_fb, abs=5e-4)
    assert settings.source("k_fb").startswith(
        "loader-model design --method optimise --solver ipopt --load empty"
    )
    assert main(["simulate", "--controller", str(target), "--duration", "3"]) == 0
    assert f"{target} controller" in capsys.readouterr().out


def test_simulate_names_the_allowed_controllers(capsys) -> None:
    assert main(["simulate", "--controller", "skyhok", "--duration", "1"]) == 2
    assert "allowed: baseline, passive, virtual-accumulator, skyhook" in capsys.readouterr().err
