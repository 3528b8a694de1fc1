"""The pump-sizing study and the command's options: rows, files, bad input."""

from __future__ import annotations

import numpy as np
import pytest

from loader_model.bound.pump_sizing import (
    plot_pump_sizing,
    pump_sizing,
    scaled_plant,
    write_csv,
)
from loader_model.simulation.scenario import ride_scenario


def test_scaled_plant_scales_one_parameter(plant):
    sized = scaled_plant(plant, "V_p_max", 2.0)
    assert sized.parameter("V_p_max") == pytest.approx(2.0 * plant.parameter("V_p_max"))
    assert sized.parameter("omega_p") == plant.parameter("omega_p")


def test_one_size_writes_its_files(plant, road, tmp_path):
    rows = pump_sizing(plant, road, factors=(1.0,), parameters=("omega_p",), duration_s=3.0)
    assert rows[0].bound_converged and np.isnan(rows[0].controller_a_total_m_s2)
    csv = write_csv(rows, tmp_path / "sizing.csv")
    assert csv.read_text().splitlines()[1].startswith("omega_p,1,")
    assert plot_pump_sizing(rows, tmp_path / "sizing.png").stat().st_size > 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sizing.csv", "sizing.png"]


@pytest.mark.slow
def test_a_smaller_pump_never_buys_more(plant, road, tmp_path):
    rows = pump_sizing(
        plant,
        road,
        factors=(0.5, 1.0),
        parameters=("V_p_max",),
        controller=lambda sized: ride_scenario(sized, "skyhook"),
        duration_s=3.0,
    )
    assert [row.factor for row in rows] == [0.5, 1.0]
    assert all(row.bound_converged for row in rows)
    assert rows[0].bound_a_total_m_s2 >= rows[1].bound_a_total_m_s2 * (1 - 1e-9)
    for row in rows:
        assert row.bound_a_total_m_s2 < row.baseline_a_total_m_s2
        assert np.isfinite(row.controller_a_total_m_s2)
    csv = write_csv(rows, tmp_path / "sizing.csv")
    assert csv.read_text().count("\n") == 3
    assert plot_pump_sizing(rows, tmp_path / "sizing.png").stat().st_size > 0


def test_bad_pump_input_names_the_argument(plant, road):
    with pytest.raises(ValueError, match="factor"):
        scaled_plant(plant, "V_p_max", 0.0)
    with pytest.raises(ValueError, match="parameter"):
        scaled_plant(plant, "stroke", 2.0)
    with pytest.raises(ValueError, match="factors"):
        pump_sizing(plant, road, factors=())
    with pytest.raises(ValueError, match="Vd_p_max"):
        pump_sizing(plant, road, factors=(-1.0,), parameters=("Vd_p_max",))


@pytest.mark.parametrize(
    ("arguments", "named"),
    [
        (["--bound", "quadratic"], "--bound"),
        (["--pump-sizing", "--factors", "0,1"], "--factors"),
        (["--duration", "0"], "--duration"),
        (["--pump-sizing"], "--output"),
    ],
)
def test_command_rejects_bad_options(arguments, named, capsys):
    from loader_model.cli import main

    assert main(["bound", *arguments]) == 2
    assert named in capsys.readouterr().err


def test_unknown_bound_kind_names_the_argument():
    from loader_model.bound.comparison import solve_bound

    with pytest.raises(ValueError, match="bound"):
        solve_bound(None, "quadratic")
