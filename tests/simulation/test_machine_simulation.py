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


# --- a tight-tolerance CVODES reference and the energy balance of the wheel loader's runs -----
# The skid-steer's are loader_model/simulation/reference.py and energy_balance.py; here the same
# construction on the machine's own plant Function and energy Function: CVODES over each 1 ms
# controller period (road table linear inside it, the command held), restarted at every period,
# the power integrals appended to the state so that one error control covers them.


def _cvodes_reference(scenario, road, duration_s: float, rtol: float = 1e-10) -> dict:
    """Rows at the controller's instants of the closed loop of ``scenario`` and its integrals."""
    import casadi as ca

    from loader_model.plant.energy import energy_function
    from loader_model.plant.plant import plant_function
    from loader_model.simulation.controllers import CONTROLLER_PERIOD_S as PERIOD_S
    from loader_model.simulation.simulator import exogenous_table

    plant_scenario = scenario.plant
    layout, params = plant_scenario.layout, np.asarray(plant_scenario.params)
    plant, energy = plant_function(MACHINE), energy_function(MACHINE)
    nx, nw, n_road = (
        len(layout.state_names),
        len(layout.exogenous_names),
        len(layout.machine.road_names),
    )
    n_in, n_loss = energy.size1_out(2), energy.size1_out(3)
    state = ca.SX.sym("state", nx + n_in + n_loss)
    t, p = ca.SX.sym("t"), ca.SX.sym("p", 1 + 2 * nw + params.size)
    u, w0, w1, theta = p[0], p[1 : 1 + nw], p[1 + nw : 1 + 2 * nw], p[1 + 2 * nw :]
    w = w0 + (w1 - w0) * (t / PERIOD_S)
    _, _, inputs, losses, _ = energy(
        state[:nx], u, w, (w1[:n_road] - w0[:n_road]) / PERIOD_S, theta
    )
    ode = ca.vertcat(plant(state[:nx], u, w, theta)[0], inputs, losses)
    options = {"reltol": rtol, "abstol": 1e-12, "max_num_steps": 100_000}
    step = ca.integrator(
        "period", "cvodes", {"x": state, "t": t, "p": p, "ode": ode}, 0.0, PERIOD_S, options
    )
    count = round(duration_s / PERIOD_S)
    exogenous = exogenous_table(road, np.arange(count + 1) * PERIOD_S)
    x = np.concatenate([plant_scenario.x0, np.zeros(n_in + n_loss)])
    z, u_held = np.asarray(scenario.controller_state, dtype=float), plant_scenario.u0
    rows, commands = [], []
    for k in range(count):
        y = np.asarray(plant(x[:nx], u_held, exogenous[k], params)[1]).ravel()
        z_next, u_k = scenario.controller(z, y, scenario.settings)
        rows.append(y)
        commands.append(float(u_k))
        parameters = np.concatenate([[float(u_k)], exogenous[k], exogenous[k + 1], params])
        x = np.asarray(step(x0=x, p=parameters)["xf"]).ravel()
        z, u_held = np.asarray(z_next).ravel(), float(u_k)
    stored = [np.asarray(energy(s, u_held, e, np.zeros(n_road), params)[1]).ravel()
              for s, e in ((plant_scenario.x0, exogenous[0]), (x[:nx], exogenous[count]))]  # fmt: skip
    return {
        "y": np.array(rows),
        "u": np.array(commands),
        "stored_change_J": stored[1] - stored[0],
        "input_work_J": x[nx : nx + n_in],
        "dissipated_J": x[nx + n_in :],
    }


def _seat_signals(y: np.ndarray, names: tuple[str, ...]) -> np.ndarray:
    index = [names.index(name) for name in ("f_Px", "f_Py", "thetadd_1")]
    return y[:, index]


@pytest.mark.parametrize("controller", ["passive", "skyhook"])
def test_course_matches_the_cvodes_reference_over_the_first_board(controller: str) -> None:
    """The simulator (ROS2, 4 substeps) against CVODES at rtol 1e-10 over the first 3 s (the
    front axle over the first board), full bucket: the seat-pad and pitch signals and the pump
    command to 6 % (r.m.s. and peak) of their excursion, the skid-steer's acceptance."""
    duration_s = 3.0
    scenario = resolve_scenario(None, "full", controller=controller, machine=MACHINE)
    road = course_input(paper_course(9.0), scenario)
    fast = simulate(road, scenario, duration_s=duration_s)
    reference = _cvodes_reference(scenario, road, duration_s)
    names = scenario.plant.layout.output_names
    want = _seat_signals(reference["y"], names)
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


def test_passive_run_balances_its_energy() -> None:
    """Road work + pump work + charge-line work = dissipation + ΔE over the first board (passive:
    the accumulator connected, the pump holding u0), from the CVODES reference's integrals."""
    scenario = resolve_scenario(None, "full", controller="passive", machine=MACHINE)
    road = course_input(paper_course(9.0), scenario)
    reference = _cvodes_reference(scenario, road, 3.0)
    inputs, losses = reference["input_work_J"], reference["dissipated_J"]
    stored = reference["stored_change_J"]
    residual = inputs.sum() - losses.sum() - stored.sum()
    largest = max(np.abs(inputs).max(), np.abs(losses).max(), np.abs(stored).max())
    assert inputs[0] > 100.0  # joules of road work: the board did work on the machine
    assert losses[0] > 10.0  # the tyres dissipated
    print(f"wheel loader passive 3 s: residual {residual:.3e} J of {largest:.1f} J")
    assert abs(residual) < 1e-6 * largest


def test_simulated_passive_run_balances_its_energy_to_its_integration_error() -> None:
    """The same balance from the simulator's 1 ms rows (trapezoid, as the skid-steer's
    ``simulated_energy_balance``): its residual is the ROS2 integration's, held to 1 % of the
    largest term (the skid-steer's acceptance), and its road work is the reference's."""
    from loader_model.plant.energy import energy_function
    from loader_model.simulation.simulator import exogenous_table

    duration_s = 3.0
    scenario = resolve_scenario(None, "full", controller="passive", machine=MACHINE)
    road = course_input(paper_course(9.0), scenario)
    result = simulate(road, scenario, duration_s=duration_s)
    layout, params = scenario.plant.layout, np.asarray(scenario.plant.params)
    time_s = np.append(result.time_s, 2 * result.time_s[-1] - result.time_s[-2])
    states = np.vstack(
        [np.column_stack([result[name] for name in layout.state_names]), result.final_state]
    )
    commands = np.append(result["V_p_ref"], result["V_p_ref"][-1])
    exogenous = exogenous_table(road, time_s)
    n_road, count = len(layout.machine.road_names), time_s.size
    mapped = energy_function(MACHINE).map(count)
    _, parts, inputs, losses, elastic = (
        np.asarray(v, dtype=float)
        for v in mapped(states.T, commands, exogenous.T, np.zeros((n_road, count)), params)
    )
    powers = np.vstack([inputs, losses])
    integrals = ((powers[:, 1:] + powers[:, :-1]) / 2 * np.diff(time_s)).sum(axis=1)
    displacement = np.diff(exogenous[:, :n_road], axis=0).T
    integrals[0] += ((elastic[:, 1:] + elastic[:, :-1]) / 2 * displacement).sum()
    n_in = inputs.shape[0]
    stored = parts[:, -1] - parts[:, 0]
    residual = integrals[:n_in].sum() - integrals[n_in:].sum() - stored.sum()
    largest = max(np.abs(integrals).max(), np.abs(stored).max())
    reference = _cvodes_reference(scenario, road, duration_s)
    print(f"simulated passive 3 s: residual {residual:.3f} J of {largest:.1f} J")
    assert abs(residual) < 1e-2 * largest
    assert integrals[0] == pytest.approx(reference["input_work_J"][0], rel=2e-2)
