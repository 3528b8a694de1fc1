"""``--machine`` on hydraulics, bound, preview and calibrate: the wheel loader's hydraulics, its
bound and preview, and a one-line refusal (exit code 2) where a command is built on the
skid-steer only."""

from __future__ import annotations

import re

import numpy as np
import pytest

from derive.description import MACHINES_DIR
from loader_model.cli import main
from loader_model.plant.plant_parameters import PlantOptions
from loader_model.plant.scenario import resolve_plant

WHEEL_LOADER = "compact_wheel_loader"


def test_hydraulics_of_the_wheel_loader(tmp_path, capsys) -> None:
    """k_eq printed for the wheel loader equals errata 6's closed form
    n K_oil A_p² (1/V_A + α²/V_B) at its static piston position (the printed value has four
    significant digits: rounding is at most 5e-4 of it), and the pressure loop is printed."""
    figure = tmp_path / "loop.png"
    assert main(["hydraulics", "--machine", WHEEL_LOADER, "--plot", str(figure)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("compact wheel loader: Hydraulic plant, bucket load empty")
    assert "Eq. 43 (the paper's skid-steer, for reference)" in out
    assert "high-pass 1 rad/s: DC gain" in out and "direct p_A feedback: DC gain" in out
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    printed = float(re.search(r"k_eq \(chambers closed\)\s+(\S+) N/m", out).group(1))
    plant = resolve_plant(None, "empty", PlantOptions.closed(), machine=WHEEL_LOADER)
    value = plant.parameter
    piston = np.pi / 4 * value("d_piston") ** 2
    annulus = piston - np.pi / 4 * value("d_rod") ** 2
    position = plant.output("x_piston")
    volume_a = piston * position + value("V_dead_A")
    volume_b = annulus * (value("stroke") - position) + value("V_dead_B")
    alpha = annulus / piston
    expected = value("n_cyl") * value("K_oil") * piston**2 * (1 / volume_a + alpha**2 / volume_b)
    assert printed == pytest.approx(expected, rel=6e-4)


# slow: the wheel loader's controllers simulated over 3 s (Wd of a_total needs 2.6 s) and over
# the whole course (seconds each)
@pytest.mark.slow
@pytest.mark.parametrize(
    ("argv", "first"),
    [
        (["bound", "--duration", "3"], "compact_wheel_loader: paper course, 9 km/h"),
        (["preview"], "compact_wheel_loader: paper course, 9 km/h"),
    ],
)
def test_bound_and_preview_run_on_the_wheel_loader(argv, first, tmp_path, capsys) -> None:
    """Exit 0 on the wheel loader, its title first, the bound below the baseline (a bound of
    the linear plant: below what the simulated baseline reaches on the course), files written."""
    output = tmp_path / "out"
    machine = ["--machine", WHEEL_LOADER, "--no-progress", "--output", str(output)]
    assert main([*argv, *machine]) == 0
    out = capsys.readouterr().out
    assert out.startswith(first)
    rows = dict(
        re.findall(r"^(baseline|bound \(linear\)|non-causal LQ bound)\D+(\d+\.\d+)", out, re.M)
    )
    bound = rows.get("bound (linear)", rows.get("non-causal LQ bound"))
    assert bound is not None and float(bound) < float(rows["baseline"]), out
    assert sorted(path.suffix for path in output.iterdir()) == [".csv", ".png"]


@pytest.mark.parametrize("argv", [["calibrate"]])
@pytest.mark.parametrize("machine", [WHEEL_LOADER, str(MACHINES_DIR / f"{WHEEL_LOADER}.toml")])
def test_skid_steer_commands_refuse_another_machine(
    argv: list[str], machine: str, tmp_path, capsys
) -> None:
    """One line naming --machine, the value given and what is allowed; nothing written."""
    assert main([*argv, "--machine", machine, "--output", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert f"--machine {machine!r}" in err and "allowed: skid_steer" in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("command", ["hydraulics", "bound", "preview", "calibrate"])
def test_an_unknown_machine_is_named(command: str, capsys) -> None:
    assert main([command, "--machine", "tractor"]) == 2
    err = capsys.readouterr().err
    assert "unknown machine 'tractor'; allowed:" in err and len(err.strip().splitlines()) == 1
