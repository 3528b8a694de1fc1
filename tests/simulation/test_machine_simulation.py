"""The compact wheel loader over the paper's course (issue 23): every controller runs, stays in the
model's range of validity, and its ISO 2631-1 evaluation at the seat pad is finite."""

from __future__ import annotations

import math

import numpy as np
import pytest

from loader_model.plant.layout import plant_layout
from loader_model.simulation.courses import paper_course
from loader_model.simulation.machine_comparison import compare_controllers, format_comparison
from loader_model.simulation.scenario import resolve_scenario
from loader_model.simulation.simulator import course_input, simulate
from loader_model.simulation.validity import validity_bounds

MACHINE = "compact_wheel_loader"


def test_validity_bounds_from_the_machine() -> None:
    scenario = resolve_scenario(None, "full", controller="baseline", machine=MACHINE)
    bounds = validity_bounds(scenario.params, layout=scenario.plant.layout)
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


# slow: 6.5 s (the wheel loader's four controllers over a course)
@pytest.mark.slow
def test_comparison_rows() -> None:
    rows = compare_controllers(plant_layout(MACHINE), None, "full", course=paper_course(9.0))
    assert [row.controller for row in rows] == [
        "baseline",
        "passive",
        "virtual-accumulator",
        "skyhook",
    ]
    assert rows[0].change_percent == 0.0
    assert all(row.valid and 0.5 < row.a_total < 20.0 for row in rows)
    assert "a_total" in format_comparison(rows)


# --- a tight-tolerance CVODES reference and the energy balance of the wheel loader's runs -----
# The library's loader_model/simulation/reference.py and energy_balance.py with machine=: CVODES
# over each 1 ms controller period (road table linear inside it, the command held), restarted at
# every period; for the balance the power integrals appended to the state so that one error
# control covers them.


def _seat_signals(y: np.ndarray, names: tuple[str, ...]) -> np.ndarray:
    index = [names.index(name) for name in ("f_Px", "f_Py", "thetadd_1")]
    return y[:, index]


@pytest.mark.parametrize("controller", ["passive", pytest.param("skyhook", marks=pytest.mark.slow)])
def test_course_matches_the_cvodes_reference_over_the_first_board(controller: str) -> None:
    """The simulator (ROS2, 4 substeps) against CVODES at rtol 1e-10 over the first 3 s (the
    front axle over the first board), full bucket: the seat-pad and pitch signals and the pump
    command to 6 % (r.m.s. and peak) of their excursion, the skid-steer's acceptance."""
    from loader_model.simulation.reference import reference_simulation

    duration_s = 3.0
    scenario = resolve_scenario(None, "full", controller=controller, machine=MACHINE)
    road = course_input(paper_course(9.0), scenario)
    fast = simulate(road, scenario, duration_s=duration_s)
    reference = reference_simulation(
        road,
        scenario.params,
        scenario.controller,
        settings=scenario.settings,
        controller_state=scenario.controller_state,
        duration_s=duration_s,
        machine=MACHINE,
    )
    layout = scenario.plant.layout
    assert reference["x"].shape == (fast.time_s.size, len(layout.state_names))
    np.testing.assert_array_equal(reference["x"][0], scenario.x0)  # from the same equilibrium
    want = _seat_signals(reference["y"], layout.output_names)
    got = np.column_stack([fast[name] for name in ("f_Px", "f_Py", "thetadd_1")])
    assert got.shape == want.shape
    error = np.sqrt(np.mean((got - want) ** 2, axis=0))
    scale = np.sqrt(np.mean((want - want[0]) ** 2, axis=0))
    assert np.all(scale > 0.05)  # m/s², rad/s²: the board really shook the machine
    assert np.all(error <= 0.06 * scale), error / scale
    np.testing.assert_allclose(
        fast["V_p_ref"], reference["u"], rtol=0.0, atol=0.06 * np.ptp(reference["u"]) + 1e-12
    )
    print(f"{controller}: r.m.s. error / excursion {np.round(error / scale, 5)}")


def test_reference_refuses_a_parameter_vector_of_another_machine() -> None:
    from loader_model.plant.scenario import resolve_plant
    from loader_model.simulation.reference import reference_simulation

    skid_steer = resolve_plant(None, "full")
    road = course_input(paper_course(9.0), resolve_scenario(None, "full", machine=MACHINE))
    with pytest.raises(ValueError, match="plant parameters of machine 'compact_wheel_loader'"):
        reference_simulation(road, skid_steer.params, duration_s=0.01, machine=MACHINE)


@pytest.mark.slow  # 3 s; the skid-steer's balance tests stay fast
def test_passive_run_balances_its_energy() -> None:
    """Road work + pump work + charge-line work = dissipation + ΔE over the first board (passive:
    the accumulator connected, the pump holding u0), by CVODES with the integrals as states; the
    locked tilt cylinder's spring and damper are booked as ``internal``."""
    from loader_model.simulation.energy_balance import reference_energy_balance

    scenario = resolve_scenario(None, "full", controller="passive", machine=MACHINE)
    road = course_input(paper_course(9.0), scenario)
    balance = reference_energy_balance(road, scenario.params, duration_s=3.0, machine=MACHINE)
    assert "internal" in balance.stored_change_J and "internal" in balance.dissipated_J
    assert balance.input_work_J["road"] > 100.0  # joules: the board did work on the machine
    assert balance.dissipated_J["tyres"] > 10.0  # the tyres dissipated
    print(f"wheel loader passive 3 s: residual {balance.residual_J:.3e} J of "
          f"{balance.largest_term_J:.1f} J")  # fmt: skip
    assert balance.relative_residual < 1e-6


@pytest.mark.slow  # 3 s
def test_simulated_passive_run_balances_its_energy_to_its_integration_error() -> None:
    """The same balance from the simulator's 1 ms rows (trapezoid): its residual is the ROS2
    integration's, held to 1 % of the largest term (the skid-steer's acceptance), and its road
    work is the reference's."""
    from loader_model.simulation.energy_balance import (
        reference_energy_balance,
        simulated_energy_balance,
    )

    duration_s = 3.0
    scenario = resolve_scenario(None, "full", controller="passive", machine=MACHINE)
    road = course_input(paper_course(9.0), scenario)
    result = simulate(road, scenario, duration_s=duration_s)
    balance = simulated_energy_balance(result, road, scenario.params, machine=MACHINE)
    reference = reference_energy_balance(road, scenario.params, duration_s=3.0, machine=MACHINE)
    print(f"simulated passive 3 s: residual {balance.residual_J:.3f} J of "
          f"{balance.largest_term_J:.1f} J")  # fmt: skip
    assert balance.relative_residual < 1e-2
    assert set(balance.dissipated_J) == set(reference.dissipated_J)
    assert balance.input_work_J["road"] == pytest.approx(reference.input_work_J["road"], rel=2e-2)
