"""``loader-model design``: output, figure, clear errors, no partial files."""

from __future__ import annotations

from pathlib import Path

import pytest

from loader_model.cli import main


def test_design_prints_gains_costs_and_writes_the_figure(tmp_path: Path, capsys) -> None:
    target = tmp_path / "fig12.png"
    assert main(["design", "--plot", str(target), "--no-check"]) == 0
    out = capsys.readouterr().out
    assert "not checked on the nonlinear machine" in out
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
        (
            ["--course", "boards"],
            "--course with --method optimise: allowed only with --method refine",
        ),
        (["--method", "lqr", "--board-height", "0.05"], "--board-height with --method lqr"),
        (
            ["--method", "refine", "--speed", "12"],
            "--speed 12: allowed with --course paper: 9 or 18",
        ),
        (["--method", "refine", "--course", "boards", "--board-height", "2"], "--board-height"),
        (["--method", "refine", "--course", "nowhere.toml"], "nowhere.toml"),
    ],
)
def test_design_errors_are_clear_and_write_nothing(
    tmp_path: Path, capsys, monkeypatch, arguments: list[str], message: str
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["design", *arguments]) == 2
    assert message in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


# slow: 12 s (an IPOPT design, its check and a simulation of the written file)
@pytest.mark.slow
def test_designed_gains_go_to_a_settings_file_that_simulate_runs(tmp_path: Path, capsys) -> None:
    from loader_model.control.settings import load_settings

    target = tmp_path / "designed.toml"
    envelope = tmp_path / "envelope.toml"
    # the linear design of the empty bucket on its own road, ISO 8608 C at 9 km/h (measured:
    # -45 % against the baseline), without the sampled plants (3 of 8 of them are unstable)
    envelope.write_text(
        '[envelope]\nloads = ["empty"]\nboard_speeds_kmh = []\nroad_classes = ["C"]\n'
        "road_speeds_kmh = [9.0]\n[criteria]\nsampled_plants = 0\n"
    )
    argv = ["design", "--load", "empty", "--solver", "ipopt", "--output", str(target)]
    assert main([*argv, "--conditions", str(envelope), "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "empty, ISO C 9 km/h" in out and "PASSED" in out
    settings = load_settings(target)
    printed = next(line for line in out.splitlines() if "optimised (ISO 2631) " in line)
    shown = [float(v) for v in printed.split("[")[1].split("]")[0].split()]
    assert shown == pytest.approx(settings.k_fb, abs=5e-4)
    assert settings.source("k_fb").startswith(
        "loader-model design --method optimise --solver ipopt --load empty"
    )
    assert "passed its design check (1 conditions, envelope file" in settings.source("k_fb")
    assert main(["simulate", "--controller", str(target), "--duration", "3"]) == 0
    assert f"{target} controller" in capsys.readouterr().out


def test_simulate_names_the_allowed_controllers(capsys) -> None:
    assert main(["simulate", "--controller", "skyhok", "--duration", "1"]) == 2
    assert "allowed: baseline, passive, virtual-accumulator, skyhook" in capsys.readouterr().err


@pytest.mark.slow  # 7.7 s: a design and its check over the envelope, twice
def test_gains_that_fail_the_check_are_not_written_unless_forced(tmp_path: Path, capsys) -> None:
    """The linear comfort design of the empty bucket makes the 40 mm boards at 9 km/h worse than
    the baseline on the nonlinear machine (the linear plant misjudges the boards): refused, the
    condition named; with --force written, the file says it failed."""
    from loader_model.control.settings import load_settings

    target = tmp_path / "designed.toml"
    envelope = tmp_path / "envelope.toml"
    envelope.write_text(
        '[envelope]\nloads = ["empty"]\nboard_speeds_kmh = [9.0]\nroad_classes = []\n'
    )
    argv = ["design", "--load", "empty", "--output", str(target), "--conditions", str(envelope)]
    assert main([*argv, "--no-progress"]) == 4
    out = capsys.readouterr().out
    assert "FAILED" in out and "empty, boards 9 km/h: a_total" in out
    assert f"not written: {target}" in out and not target.exists()
    assert main([*argv, "--no-progress", "--force"]) == 4
    header = target.read_text(encoding="utf-8").splitlines()[0]
    assert "WRITTEN WITH --force: FAILED its design check" in header
    assert "FAILED its design check" in load_settings(target).source("k_fb")


def test_no_check_with_output_needs_force(tmp_path: Path, capsys) -> None:
    target = tmp_path / "designed.toml"
    assert main(["design", "--no-check", "--output", str(target)]) == 2
    assert "--output with --no-check" in capsys.readouterr().err
    assert not target.exists()


def test_start_is_for_the_machine_method_only(tmp_path: Path, capsys) -> None:
    argv = ["design", "--method", "optimise", "--start", "default", "--no-check"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "--start default with --method optimise: allowed only with --method machine" in err
