"""The compact wheel loader over the paper's course (issue 23): every controller runs, stays in the
model's range of validity, and its ISO 2631-1 evaluation at the seat pad is finite."""

from __future__ import annotations

import math

import numpy as np
import pytest

from loader_model.simulation.courses import paper_course
from loader_model.simulation.machine_comparison import compare_controllers, format_comparison
from loader_model.simulation.scenario import resolve_scenario
from loader_model.simulation.simulator import course_input, simulate
from loader_model.simulation.validity import validity_bounds

MACHINE = "compact_wheel_loader"


def test_validity_bounds_from_the_machine() -> None:
    scenario = resolve_scenario(None, "full", controller="baseline", machine=MACHINE)
    bounds = validity_bounds(scenario.params, machine=MACHINE)
    # the bucket's 950 kg far ahead: it tips forward long before it tips back
    assert 0.3 < bounds.pitch_down_rad < bounds.pitch_up_rad < math.pi / 2
    assert 0.0 < bounds.boom_down_rad < bounds.boom_up_rad < math.pi


@pytest.mark.parametrize("controller", ["baseline", "skyhook"])
def test_course_runs_valid_and_finite(controller: str) -> None:
    scenario = resolve_scenario(None, "full", controller=controller, machine=MACHINE)
    result = simulate(course_input(paper_course(9.0), scenario), scenario, duration_s=6.0)
    assert result.metadata["machine"] == MACHINE
    assert "theta_3" in result.columns and "psi" in result.columns
    assert all(np.all(np.isfinite(values)) for values in result.columns.values())
    total = result.seat_evaluation().total_m_s2
    assert 0.5 < total < 20.0


def test_comparison_rows() -> None:
    rows = compare_controllers(MACHINE, None, "full", course=paper_course(9.0))
    assert [row.controller for row in rows] == [
        "baseline",
        "passive",
        "virtual-accumulator",
        "skyhook",
    ]
    assert rows[0].change_percent == 0.0
    assert all(row.valid and 0.5 < row.a_total < 20.0 for row in rows)
    assert "a_total" in format_comparison(rows)
