"""A run's column units for a machine other than the skid-steer: the coordinates its description
names are lengths (its length coordinates) or angles, their rates per second, and its joint
angles in rad; the skid-steer's columns keep the units of the simulation's table."""

from __future__ import annotations

import pytest

from loader_model.machines import machine
from loader_model.simulation.courses import board_course_at
from loader_model.simulation.result import COLUMN_UNITS, machine_units
from loader_model.simulation.scenario import resolve_scenario
from loader_model.simulation.simulator import course_input, simulate


def test_the_tractors_described_columns_have_their_units(tmp_path) -> None:
    scenario = resolve_scenario(None, "full", machine="tractor_front_loader")
    course = board_course_at(9.0, count=1, settle_s=2.0)
    result = simulate(course_input(course, scenario), scenario, duration_s=2.7)
    expected = {
        "theta_3": "rad", "thetad_3": "rad/s", "s_cab": "m", "sd_cab": "m/s", "psi": "rad",
        "x_H": "m", "thetad_1": "rad/s",
    }  # fmt: skip
    assert {name: result.unit(name) for name in expected} == expected
    header = result.write(tmp_path / "run.csv").read_text(encoding="utf-8").splitlines()[0]
    assert "theta_3 [rad]" in header and "s_cab [m]" in header
    info = machine("tractor_front_loader")
    for name in (*info.coordinate_names, *info.rate_names, *info.joint_angles):
        assert f"{name} [-]" not in header, name


@pytest.mark.parametrize("name", ["skid_steer", "compact_wheel_loader", "tractor_front_loader"])
def test_described_units_agree_with_the_simulations_table(name: str) -> None:
    info = machine(name)
    units = machine_units(info)
    assert set(units) >= set(info.coordinate_names) | set(info.rate_names)
    for column, unit in units.items():
        assert COLUMN_UNITS.get(column, unit) == unit, column
